// Typesets the page's math with KaTeX (loaded only on pages with `math: true`).
// kramdown writes $$..$$ as \[..\] (display, alone in a paragraph) or \(..\) (inline);
// $$..$$ is listed too for math written in raw HTML. Code blocks are skipped by
// auto-render. A formula KaTeX cannot parse stays as its TeX source and is reported on
// the console, where the page tests look for errors.
(function () {
  "use strict";

  function typeset() {
    if (typeof renderMathInElement !== "function") {
      console.error("KaTeX auto-render is not loaded: run `make build` (tools/copy-vendor.sh).");
      return;
    }
    renderMathInElement(document.querySelector(".page-body") || document.body, {
      delimiters: [
        { left: "$$", right: "$$", display: true },
        { left: "\\[", right: "\\]", display: true },
        { left: "\\(", right: "\\)", display: false }
      ],
      throwOnError: true,
      errorCallback: function (message, error) {
        console.error("KaTeX: " + message, error);
      }
    });
  }

  // Scripts are deferred, so KaTeX and auto-render have run when this one does.
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", typeset);
  else typeset();
})();
