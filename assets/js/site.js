// Behaviour of every page: the phone menu, copy buttons on code blocks, heading links,
// the image lightbox and the keyboard reaching wide formulas. Everything here improves a
// page that already works without scripts: navigation, tables of contents, badges,
// captions and formulas are in the HTML.
(function () {
  "use strict";

  // ---- Phone menu: the button in the header shows and hides the sidebar. ----------
  function setUpMenu() {
    var button = document.querySelector(".nav-toggle");
    var sidebar = document.getElementById("sidebar");
    if (!button || !sidebar) return;

    function setOpen(open) {
      button.setAttribute("aria-expanded", open ? "true" : "false");
      document.body.classList.toggle("nav-open", open);
    }

    button.addEventListener("click", function () {
      setOpen(button.getAttribute("aria-expanded") !== "true");
    });
    // Escape closes the menu and gives focus back to its button.
    document.addEventListener("keydown", function (event) {
      if (event.key === "Escape" && document.body.classList.contains("nav-open")) {
        setOpen(false);
        button.focus();
      }
    });
    // Following a link in the menu closes it (matters for links within the page), and
    // so does a tap on the dimmed page beside it.
    document.addEventListener("click", function (event) {
      if (!document.body.classList.contains("nav-open")) return;
      var inSidebar = sidebar.contains(event.target);
      if ((inSidebar && event.target.closest("a")) ||
          (!inSidebar && !button.contains(event.target))) {
        setOpen(false);
      }
    });
  }

  // ---- Copy buttons -------------------------------------------------------------
  // navigator.clipboard exists only in secure contexts (https, localhost); a site served
  // on a LAN address over http falls back to a hidden textarea and execCommand.
  function copyText(text) {
    if (navigator.clipboard && window.isSecureContext) {
      return navigator.clipboard.writeText(text);
    }
    return new Promise(function (resolve, reject) {
      var area = document.createElement("textarea");
      area.value = text;
      area.setAttribute("readonly", "");
      area.style.position = "fixed";
      area.style.top = "-1000px";
      document.body.appendChild(area);
      area.select();
      var ok = false;
      try {
        ok = document.execCommand("copy");
      } catch (error) {
        ok = false;
      }
      document.body.removeChild(area);
      if (ok) resolve();
      else reject(new Error("copy refused"));
    });
  }

  function addCopyButtons() {
    var blocks = document.querySelectorAll(".page-body pre");
    Array.prototype.forEach.call(blocks, function (pre) {
      // kramdown blocks carry a header from _plugins/code_blocks.rb; other <pre>
      // (raw HTML, {% highlight %}) get an empty one here.
      var block = pre.closest(".highlighter-rouge, figure.highlight") || pre;
      var header = block.querySelector(".code-header");
      if (!header) {
        header = document.createElement("div");
        header.className = "code-header";
        if (block === pre) pre.parentNode.insertBefore(header, pre);
        else block.insertBefore(header, block.firstChild);
      }

      var button = document.createElement("button");
      button.type = "button";
      button.className = "copy-button";
      button.textContent = "Copy";
      button.setAttribute("aria-label", "Copy code");
      // Announces the result to screen readers without moving focus.
      var status = document.createElement("span");
      status.className = "visually-hidden";
      status.setAttribute("role", "status");

      var timer = null;
      button.addEventListener("click", function () {
        var code = pre.querySelector("code") || pre;
        copyText(code.textContent.replace(/\n$/, "")).then(
          function () { show("Copied"); },
          function () { show("Press Ctrl+C"); selectText(code); }
        );
      });
      function show(message) {
        button.textContent = message;
        status.textContent = message === "Copied" ? "Code copied" : "Copy failed: select and copy by hand";
        clearTimeout(timer);
        timer = setTimeout(function () {
          button.textContent = "Copy";
          status.textContent = "";
        }, 2000);
      }
      header.appendChild(button);
      header.appendChild(status);
    });
  }

  function selectText(node) {
    var range = document.createRange();
    range.selectNodeContents(node);
    var selection = window.getSelection();
    selection.removeAllRanges();
    selection.addRange(range);
  }

  // ---- Heading links: a "#" after each h2-h4 to copy a link to that section. -------
  function addHeadingLinks() {
    var headings = document.querySelectorAll(".page-body h2[id], .page-body h3[id], .page-body h4[id]");
    Array.prototype.forEach.call(headings, function (heading) {
      var link = document.createElement("a");
      link.className = "heading-link";
      link.href = "#" + heading.id;
      link.setAttribute("aria-label", "Link to this section: " + heading.textContent);
      link.textContent = "#";
      heading.appendChild(link);
    });
  }

  // ---- Lightbox: an image in the page body opens full size in a modal dialog. -------
  // <dialog> gives focus trapping, Escape to close and the backdrop for free; the image
  // is wrapped in a button so it can be reached and opened with the keyboard.
  function setUpLightbox() {
    var images = document.querySelectorAll(".page-body img");
    if (!images.length || typeof HTMLDialogElement !== "function") return;

    var dialog = document.createElement("dialog");
    dialog.className = "lightbox";
    dialog.setAttribute("aria-label", "Enlarged image");
    var big = document.createElement("img");
    big.className = "lightbox-image";
    big.alt = "";
    var close = document.createElement("button");
    close.type = "button";
    close.className = "lightbox-close";
    close.textContent = "Close";
    dialog.appendChild(close);
    dialog.appendChild(big);
    document.body.appendChild(dialog);

    var opener = null;
    close.addEventListener("click", function () { dialog.close(); });
    // A click anywhere (image or backdrop) closes, as on most image viewers.
    dialog.addEventListener("click", function (event) {
      if (event.target !== close) dialog.close();
    });
    dialog.addEventListener("close", function () {
      document.body.classList.remove("lightbox-open");
      big.removeAttribute("src");
      if (opener) opener.focus();
    });

    Array.prototype.forEach.call(images, function (image) {
      if (image.closest("a, button")) return; // already a link: leave it one
      var button = document.createElement("button");
      button.type = "button";
      button.className = "zoom-button";
      var what = image.getAttribute("alt");
      button.setAttribute("aria-label", "Enlarge image" + (what ? ": " + what : ""));
      // Figures with a phone variant: the button takes the whole <picture>, which
      // chooses the variant (_plugins/phone_figures.rb), and the enlarged view opens the
      // figure at full size, the <img>'s own src, whichever variant the page shows (and
      // its srcset: a picture's sharp file on a screen that needs it, _plugins/sharp_images.rb;
      // the srcset's widths are read against the figure's own width, set first in sizes).
      var shown = image.parentNode.nodeName === "PICTURE" ? image.parentNode : image;
      shown.parentNode.insertBefore(button, shown);
      button.appendChild(shown);
      button.addEventListener("click", function () {
        opener = button;
        var sharp = image.getAttribute("srcset");
        if (sharp) {
          big.setAttribute("sizes", (image.getAttribute("width") || image.naturalWidth) + "px");
          big.setAttribute("srcset", sharp);
        } else {
          big.removeAttribute("srcset");
          big.removeAttribute("sizes");
        }
        big.src = image.src;
        big.alt = image.getAttribute("alt") || "";
        document.body.classList.add("lightbox-open");
        dialog.showModal();
        close.focus();
      });
    });
  }

  // ---- Formulas: one wider than the page scrolls sideways in its own line ----------
  // (.katex-display in main.css; the formulas are typeset when the site is built). Only
  // one that scrolls joins the tab order, so that keyboard users can scroll it too.
  function letWideFormulasScroll() {
    var formulas = document.querySelectorAll(".katex-display");
    if (!formulas.length) return;

    function mark() {
      formulas.forEach(function (formula) {
        if (formula.scrollWidth > formula.clientWidth) formula.setAttribute("tabindex", "0");
        else formula.removeAttribute("tabindex");
      });
    }

    mark();
    // KaTeX's fonts change the formulas' widths once they load, and a turned phone the page's.
    if (document.fonts) document.fonts.ready.then(mark);
    window.addEventListener("resize", mark);
  }

  // ---- Formulas that scroll show which way: more-left / more-right -----------------
  // A formula wider than its column (letWideFormulasScroll above) gets a shadow at each
  // edge beyond which more of it lies (.katex-display.more-left/.more-right in main.css),
  // however little is hidden; without scripts a background-only shadow stands in.
  function showWhereFormulasContinue() {
    var formulas = document.querySelectorAll(".katex-display");
    if (!formulas.length) return;

    function mark(formula) {
      var hidden = formula.scrollWidth - formula.clientWidth;
      formula.classList.toggle("more-left", hidden > 1 && formula.scrollLeft > 1);
      formula.classList.toggle("more-right", hidden > 1 && formula.scrollLeft < hidden - 1);
    }
    function markAll() { formulas.forEach(mark); }

    formulas.forEach(function (formula) {
      formula.addEventListener("scroll", function () { mark(formula); }, { passive: true });
    });
    markAll();
    if (document.fonts) document.fonts.ready.then(markAll);
    window.addEventListener("resize", markAll);
  }

  // ---- Code that scrolls shows it, and can wrap instead ---------------------------
  // A code block with a line longer than its box scrolls sideways (main.css, "Code that
  // scrolls"): a shadow marks each edge beyond which more of it lies, and a Wrap button in
  // its header wraps the long lines of every code block instead. The choice is kept for
  // the whole site (localStorage) and the button shows on the blocks that need it.
  var WRAP_KEY = "sw2sim-code-wrap";

  function storedWrap() {
    try {
      return window.localStorage.getItem(WRAP_KEY) === "1";
    } catch (error) {
      return false; // storage refused (private browsing, file://): no memory, still works
    }
  }

  function storeWrap(on) {
    try {
      if (on) window.localStorage.setItem(WRAP_KEY, "1");
      else window.localStorage.removeItem(WRAP_KEY);
    } catch (error) { /* not kept: the page still wraps */ }
  }

  function setUpCodeScrolling() {
    var pres = Array.prototype.filter.call(document.querySelectorAll(".page-body div.highlighter-rouge pre"),
      function (pre) { return !pre.closest(".language-text"); });
    if (!pres.length) return;
    var root = document.documentElement;
    var buttons = [];

    function mark(pre) {
      var block = pre.closest("div.highlighter-rouge");
      var hidden = pre.scrollWidth - pre.clientWidth;
      block.classList.toggle("more-left", hidden > 1 && pre.scrollLeft > 1);
      block.classList.toggle("more-right", hidden > 1 && pre.scrollLeft < hidden - 1);
    }
    function markAll() { pres.forEach(mark); }

    function setWrap(on) {
      root.classList.toggle("code-wrap", on);
      buttons.forEach(function (button) { button.setAttribute("aria-pressed", on ? "true" : "false"); });
      markAll();
    }

    // Which blocks have a line too long for their box, measured with the lines kept: at
    // the start, once the fonts are in and when the window changes (a turned phone).
    function addButtons() {
      var on = root.classList.contains("code-wrap");
      root.classList.remove("code-wrap");
      pres.forEach(function (pre) {
        var header = pre.closest("div.highlighter-rouge").querySelector(".code-header");
        if (!header || header.querySelector(".wrap-button")) return;
        if (pre.scrollWidth - pre.clientWidth <= 1) return;
        var button = document.createElement("button");
        button.type = "button";
        button.className = "wrap-button";
        button.textContent = "Wrap";
        button.title = "Wrap long lines in every code block (remembered on this site)";
        button.addEventListener("click", function () {
          var wrap = !root.classList.contains("code-wrap");
          storeWrap(wrap);
          setWrap(wrap);
        });
        header.insertBefore(button, header.querySelector(".copy-button"));
        buttons.push(button);
      });
      setWrap(on);
    }

    pres.forEach(function (pre) {
      pre.addEventListener("scroll", function () { mark(pre); }, { passive: true });
    });
    root.classList.toggle("code-wrap", storedWrap());
    addButtons();
    if (document.fonts) document.fonts.ready.then(addButtons);
    window.addEventListener("resize", addButtons);
  }

  // ---- Checklists a reader can tick -----------------------------------------------
  // _plugins/task_lists.rb leaves a page's checklist a plain list; here each item gets a
  // checkbox, and the ticks are kept per page in localStorage (key: CHECKLIST_KEY and the
  // page's path; value: the ticked items' texts), with a button that clears them. The
  // sidebar's links to pages with a checklist carry their number of items
  // (data-checklist): each practice shows how many of its items are ticked.
  var CHECKLIST_KEY = "sw2sim-checklist:";

  function readTicks(path) {
    try {
      var stored = JSON.parse(window.localStorage.getItem(CHECKLIST_KEY + path) || "[]");
      return Array.isArray(stored) ? stored : [];
    } catch (error) {
      return [];
    }
  }

  function writeTicks(path, ticked) {
    try {
      if (ticked.length) window.localStorage.setItem(CHECKLIST_KEY + path, JSON.stringify(ticked));
      else window.localStorage.removeItem(CHECKLIST_KEY + path);
    } catch (error) { /* not kept: the boxes still tick */ }
  }

  function setUpChecklists() {
    var path = window.location.pathname;
    var lists = document.querySelectorAll(".page-body ul.task-list");
    var boxes = [];
    Array.prototype.forEach.call(lists, function (list, listNumber) {
      list.classList.add("checklist");
      Array.prototype.forEach.call(list.querySelectorAll(":scope > li.task-list-item"), function (item, n) {
        var text = item.textContent.trim().replace(/\s+/g, " ");
        var box = document.createElement("input");
        box.type = "checkbox";
        box.className = "task-list-item-checkbox";
        box.id = "check-" + listNumber + "-" + n;
        box.value = text;
        var label = document.createElement("label");
        label.className = "task-list-label";
        label.htmlFor = box.id;
        // The item's own text (and inline markup) becomes the label; a nested list stays after it.
        while (item.firstChild && !/^(UL|OL|P|DIV)$/.test(item.firstChild.nodeName)) {
          label.appendChild(item.firstChild);
        }
        item.insertBefore(label, item.firstChild);
        item.insertBefore(box, label);
        boxes.push(box);
      });
      var clear = document.createElement("button");
      clear.type = "button";
      clear.className = "checklist-clear";
      clear.textContent = "Clear the ticks";
      clear.addEventListener("click", function () {
        boxes.forEach(function (box) { box.checked = false; });
        save();
      });
      list.parentNode.insertBefore(clear, list.nextSibling);
    });

    function save() {
      writeTicks(path, boxes.filter(function (box) { return box.checked; })
        .map(function (box) { return box.value; }));
      showProgress();
    }

    var ticked = readTicks(path);
    boxes.forEach(function (box) {
      box.checked = ticked.indexOf(box.value) >= 0;
      box.addEventListener("change", save);
    });
    showProgress();
  }

  // Beside each practice in the sidebar: ticked / items over its pages' checklists.
  function showProgress() {
    var sections = document.querySelectorAll(".sidebar-nav .nav-section");
    Array.prototype.forEach.call(sections, function (section) {
      var total = 0;
      var done = 0;
      section.querySelectorAll("a.nav-link[data-checklist]").forEach(function (link) {
        var items = parseInt(link.getAttribute("data-checklist"), 10) || 0;
        total += items;
        done += Math.min(items, readTicks(new URL(link.href, window.location.href).pathname).length);
      });
      var summary = section.querySelector("summary");
      if (!total || !summary) return;
      var badge = summary.querySelector(".checklist-progress");
      if (!badge) {
        badge = document.createElement("span");
        badge.className = "checklist-progress";
        summary.appendChild(badge);
      }
      badge.textContent = done + "/" + total;
      badge.title = done + " of " + total + " checklist items ticked";
      badge.setAttribute("aria-label", badge.title);
      badge.classList.toggle("checklist-done", done === total);
    });
  }

  // ---- Tables that scroll show which way: more-left / more-right -------------------
  // A table wider than its box (_plugins/tables.rb) gets a shadow at each edge beyond
  // which more of it lies (.table-box in main.css); with its first column pinned, the
  // left shadow starts where that column ends.
  function showWhereTablesContinue() {
    var boxes = document.querySelectorAll(".table-box");
    if (!boxes.length) return;

    function mark(box) {
      var wrap = box.querySelector(".table-wrap");
      if (!wrap) return;
      var hidden = wrap.scrollWidth - wrap.clientWidth;
      box.classList.toggle("more-left", hidden > 1 && wrap.scrollLeft > 1);
      box.classList.toggle("more-right", hidden > 1 && wrap.scrollLeft < hidden - 1);
      var first = box.classList.contains("table-pinned") && wrap.querySelector("tr > :first-child");
      var pinned = first && getComputedStyle(first).position === "sticky" ? first.offsetWidth : 0;
      box.style.setProperty("--pinned-width", pinned + "px");
    }
    function markAll() { boxes.forEach(mark); }

    boxes.forEach(function (box) {
      var wrap = box.querySelector(".table-wrap");
      if (wrap) wrap.addEventListener("scroll", function () { mark(box); }, { passive: true });
    });
    markAll();
    if (document.fonts) document.fonts.ready.then(markAll);
    window.addEventListener("resize", markAll);
  }

  function start() {
    setUpMenu();
    addCopyButtons();
    setUpCodeScrolling();
    setUpChecklists();
    addHeadingLinks();
    setUpLightbox();
    letWideFormulasScroll();
    showWhereFormulasContinue();
    showWhereTablesContinue();
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
