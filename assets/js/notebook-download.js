// The "Download this lesson as a Jupyter notebook" link (_includes/notebook-link.html)
// hands over the notebook with this site's address written into its first cell, so that
// the notebook fetches the lesson's files from wherever the reader found it: the Pages
// site, a copy on a LAN, or `make serve` on http://127.0.0.1:4000. The site's build only
// knows its address when it is given one (_plugins/notebooks.rb: url and baseurl, as the
// Pages workflow sets them); a local build publishes notebooks with no address, which
// would stop in their first cell unless SW2SIM_COURSE_SITE were set.
//
// On the first click the notebook is fetched, `site="..."` in its setup cell (the cell
// tagged "setup", course/notebook_setup.py) becomes the address the page was served from,
// and the result is downloaded from memory under the same name. Should anything fail, the
// link downloads the published file as it is; without scripts it does so anyway, and the
// paragraph says what to set.
(function () {
  "use strict";

  // The setup function's parameter, `site="..."`, as course/notebook_setup.py writes it.
  var SITE_PARAMETER = /\bsite="(?:[^"\\]|\\.)*"/;

  // The address of the site this page came from, without a trailing slash:
  // the link's data-notebook-site is the site's root ('/' plus the baseurl).
  function siteAddress(link) {
    var root = new URL(link.getAttribute("data-notebook-site"), window.location.href);
    return (root.origin + root.pathname).replace(/\/+$/, "");
  }

  // The notebook (parsed JSON) with the site's address in its setup cell; false when it
  // has no such cell.
  function withSite(notebook, site) {
    var cell = (notebook.cells || []).filter(function (c) {
      var tags = (c.metadata && c.metadata.tags) || [];
      return c.cell_type === "code" && tags.indexOf("setup") >= 0;
    })[0];
    if (!cell) return false;
    var source = Array.isArray(cell.source) ? cell.source.join("") : String(cell.source);
    if (!SITE_PARAMETER.test(source)) return false;
    // A JSON string is a Python string literal too (the build writes it the same way).
    source = source.replace(SITE_PARAMETER, function () { return "site=" + JSON.stringify(site); });
    // nbformat's layout: a list of lines, each but the last with its newline.
    cell.source = source.match(/[^\n]*\n|[^\n]+$/g) || [];
    return true;
  }

  function setUp(link) {
    var ready = false;
    link.addEventListener("click", function (event) {
      if (ready) return; // the second, scripted click: the browser downloads
      event.preventDefault();
      var name = link.getAttribute("download") || "lesson.ipynb";
      fetch(link.href)
        .then(function (response) {
          if (!response.ok) throw new Error(response.status + " " + response.statusText);
          return response.json();
        })
        .then(function (notebook) {
          if (!withSite(notebook, siteAddress(link))) throw new Error("no setup cell");
          var text = JSON.stringify(notebook, null, 1) + "\n";
          link.href = URL.createObjectURL(new Blob([text], { type: "application/x-ipynb+json" }));
          link.setAttribute("download", name);
        })
        .catch(function () { /* the published file, as it is */ })
        .then(function () {
          ready = true;
          link.click();
        });
    });
  }

  function start() {
    var links = document.querySelectorAll("a[data-notebook-site]");
    if (!window.fetch || !window.Blob || !window.URL || !URL.createObjectURL) return;
    Array.prototype.forEach.call(links, setUp);
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
