// "On this page" follows the reader: the entry of the section in view is marked with
// aria-current="location" (styled in main.css) as the page scrolls. The section in view
// is the last one whose heading has passed a line a third of the way down the window.
// An IntersectionObserver tells when a heading crosses that line, so nothing runs on
// every scroll event. Without the script the box is a plain list of links.
(function () {
  "use strict";

  function start() {
    var toc = document.querySelector(".toc:not([hidden])");
    if (!toc || typeof IntersectionObserver !== "function") return;

    var sections = [];
    Array.prototype.forEach.call(toc.querySelectorAll('.toc-list a[href^="#"]'), function (link) {
      var heading = document.getElementById(decodeURIComponent(link.hash.slice(1)));
      if (heading) sections.push({ heading: heading, link: link });
    });
    if (!sections.length) return;

    var current = null;
    var header = document.querySelector(".site-header");

    function line() {
      var below = header ? header.getBoundingClientRect().bottom : 0;
      return below + (window.innerHeight - below) / 3;
    }

    function update() {
      var at = line();
      var found = null;
      for (var i = 0; i < sections.length; i++) {
        if (sections[i].heading.getBoundingClientRect().top <= at) found = sections[i];
        else break;
      }
      // At the very end of the page the last sections may never reach the line.
      var page = document.documentElement;
      if (window.innerHeight + window.scrollY >= page.scrollHeight - 2) {
        for (var j = sections.length - 1; j >= 0; j--) {
          if (sections[j].heading.getBoundingClientRect().top < window.innerHeight) {
            found = sections[j];
            break;
          }
        }
      }
      if (found === current) return;
      if (current) current.link.removeAttribute("aria-current");
      current = found;
      if (current) {
        current.link.setAttribute("aria-current", "location");
        keepInView(current.link);
      }
    }

    // The box scrolls on its own when it is taller than the window (wide screens):
    // bring the marked entry into it without moving the page.
    function keepInView(link) {
      if (toc.scrollHeight <= toc.clientHeight) return;
      var box = toc.getBoundingClientRect();
      var item = link.getBoundingClientRect();
      if (item.top < box.top) toc.scrollTop -= box.top - item.top + 8;
      else if (item.bottom > box.bottom) toc.scrollTop += item.bottom - box.bottom + 8;
    }

    var observer = null;
    function observe() {
      if (observer) observer.disconnect();
      // A band from the top of the window down to the line: a heading entering or
      // leaving it has crossed the line one way or the other.
      var bottom = Math.max(0, Math.round(window.innerHeight - line()));
      observer = new IntersectionObserver(update, { rootMargin: "0px 0px -" + bottom + "px 0px" });
      sections.forEach(function (section) { observer.observe(section.heading); });
    }

    observe();
    window.addEventListener("resize", observe);
    // The end of the page crosses no heading: check there once scrolling stops.
    window.addEventListener("scrollend", update);
    update();
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
