// The site search: the box in the header (_includes/search.html).
//
// lunr and the documents (assets/search-data.json, one per page section, written by
// _plugins/search_index.rb) are fetched on the first focus of the box, and the index is
// built here in the browser: for this site it takes a few tens of milliseconds, and the
// documents are smaller than a prebuilt index would be. Each result links to its
// section's heading and shows the page it is on and the text around the first match.
//
// Keyboard: "/" anywhere focuses the box; Enter opens the first result; the down and up
// arrows move between the box and the results; Escape closes the results.
(function () {
  "use strict";

  const form = document.querySelector(".site-search");
  if (!form) return;
  const input = form.querySelector(".site-search-input");
  const panel = form.querySelector(".site-search-results");
  const status = form.querySelector(".site-search-status");
  const list = form.querySelector(".site-search-list");

  const MAX_RESULTS = 10;
  const EXCERPT_BEFORE = 60; // characters shown before the first match
  const EXCERPT_LENGTH = 160;
  // A section's heading (the page title for the text above the first heading) counts
  // most, then the names in its code and the title of its page (which says what every
  // section of the page is about), then its text.
  const FIELDS = [["title", 8], ["code", 2], ["page", 2], ["text", 1]];
  // Words end at spaces and punctuation, dots and slashes included, so that
  // "sw2sim.load_package(path)" gives sw2sim, load_package and path; `_` stays inside
  // a word, so identifiers are found whole.
  const SEPARATOR = /[\s\-–—/.,;:!?()[\]{}<>=+*"'‘’“”|]+/;

  let searcher = null; // promise of the search function, once loading has started
  let docs = [];

  // ---- Loading ------------------------------------------------------------------
  function loadScript(src) {
    return new Promise((resolve, reject) => {
      const script = document.createElement("script");
      script.src = src;
      script.onload = resolve;
      script.onerror = () => reject(new Error(`could not load ${src}`));
      document.head.appendChild(script);
    });
  }

  function load() {
    if (!searcher) {
      const documents = fetch(form.dataset.documents).then((response) => {
        if (!response.ok) throw new Error(`${response.status} for ${response.url}`);
        return response.json();
      });
      searcher = Promise.all([loadScript(form.dataset.lunr), documents])
        .then(([, loaded]) => buildSearch(loaded));
      // A failed load (offline, say) is tried again on the next search.
      searcher.catch(() => { searcher = null; });
    }
    return searcher;
  }

  function buildSearch(loaded) {
    docs = loaded;
    lunr.tokenizer.separator = SEPARATOR;
    const index = lunr(function () {
      this.ref("id");
      FIELDS.forEach(([name, boost]) => this.field(name, { boost }));
      this.metadataWhitelist = ["position"];
      docs.forEach((doc, id) => {
        const title = doc.section || doc.page;
        this.add({ id, title, page: doc.page, text: doc.text, code: doc.code });
      });
    });
    return (text) => find(index, text);
  }

  // ---- Searching ----------------------------------------------------------------
  // The query's words, as the index holds them: lower case, no stop words ("the", "of").
  // A single letter ("s" of "wheel's") only counts when it is all there is; a digit
  // does ("practice 3").
  function words(text) {
    const all = lunr.tokenizer(text).map(String).filter((word) => lunr.stopWordFilter(word));
    const kept = all.filter((word) => !/^[a-z]$/.test(word));
    return kept.length ? kept : all;
  }

  // Every word must match. While the last word is still being typed it also counts as the
  // start of a longer word ("acker" finds "Ackermann"); whole-word matches come first.
  function find(index, text) {
    const terms = words(text);
    if (!terms.length) return [];
    const found = query(index, terms, false);
    if (/\s$/.test(text) || terms[terms.length - 1].length < 2) return found;
    const seen = new Set(found.map((match) => match.ref));
    return found.concat(query(index, terms, true).filter((match) => !seen.has(match.ref)));
  }

  function query(index, terms, lastIsPrefix) {
    return index.query((q) => {
      terms.forEach((term, i) => {
        const prefix = lastIsPrefix && i === terms.length - 1;
        q.term(term, {
          presence: lunr.Query.presence.REQUIRED,
          wildcard: prefix ? lunr.Query.wildcard.TRAILING : lunr.Query.wildcard.NONE,
          // The index holds stems ("steering" as "steer"); a prefix is matched as typed.
          usePipeline: !prefix,
        });
      });
    });
  }

  // ---- Showing the results ----------------------------------------------------------
  // [start, length] of every match of `field` in a result, in order.
  function spots(match, field) {
    const metadata = match.matchData.metadata;
    return Object.keys(metadata)
      .flatMap((term) => (metadata[term][field] ? metadata[term][field].position : []))
      .sort((a, b) => a[0] - b[0]);
  }

  // text[from:to] as text nodes, with each match inside a <mark>.
  function marked(text, where, from = 0, to = text.length) {
    const nodes = [];
    let at = from;
    where.forEach(([start, length]) => {
      if (start < at || start + length > to) return;
      nodes.push(document.createTextNode(text.slice(at, start)));
      const mark = document.createElement("mark");
      mark.textContent = text.slice(start, start + length);
      nodes.push(mark);
      at = start + length;
    });
    nodes.push(document.createTextNode(text.slice(at, to)));
    return nodes;
  }

  // The text around the first match, cut at spaces; or the names in the code that
  // matched; or the start of the section.
  function excerpt(doc, match) {
    const line = document.createElement("p");
    line.className = "site-search-excerpt";
    const inText = spots(match, "text");
    const inCode = spots(match, "code");
    if (!inText.length && inCode.length) {
      const names = [...new Set(inCode.map(([start, length]) => doc.code.substr(start, length)))];
      line.append("In the code: ");
      names.forEach((name, i) => {
        const code = document.createElement("code");
        const mark = document.createElement("mark");
        mark.textContent = name;
        code.append(mark);
        line.append(...(i ? [", ", code] : [code]));
      });
      return line;
    }
    const text = doc.text;
    let start = inText.length ? Math.max(0, inText[0][0] - EXCERPT_BEFORE) : 0;
    if (start > 0) start = text.indexOf(" ", start) + 1 || start;
    let end = Math.min(text.length, start + EXCERPT_LENGTH);
    const lastSpace = text.lastIndexOf(" ", end);
    if (end < text.length && lastSpace > start) end = lastSpace;
    line.append(...(start > 0 ? ["… "] : []), ...marked(text, inText, start, end),
                ...(end < text.length ? [" …"] : []));
    return line;
  }

  function resultItem(match) {
    const doc = docs[Number(match.ref)];
    const item = document.createElement("li");
    item.className = "site-search-hit";
    const link = document.createElement("a");
    link.className = "site-search-link";
    link.href = doc.url;
    link.append(...marked(doc.section || doc.page, spots(match, "title")));
    item.append(link);
    if (doc.section) {
      const page = document.createElement("p");
      page.className = "site-search-page";
      page.textContent = doc.page;
      item.append(page);
    }
    item.append(excerpt(doc, match));
    return item;
  }

  function render(text, found) {
    list.replaceChildren(...found.slice(0, MAX_RESULTS).map(resultItem));
    list.hidden = !found.length;
    const quoted = `“${text.trim()}”`;
    if (!found.length) {
      status.textContent = `No results for ${quoted}. Try fewer words or another spelling.`;
    } else if (found.length > MAX_RESULTS) {
      status.textContent =
        `${found.length} results for ${quoted}; the best ${MAX_RESULTS} are listed.`;
    } else {
      status.textContent = `${found.length} result${found.length === 1 ? "" : "s"} for ${quoted}.`;
    }
  }

  function failed() {
    status.textContent = "The search could not be loaded. Check the connection and try again.";
    list.hidden = true;
  }

  // ---- Opening and closing ------------------------------------------------------
  function setOpen(open) {
    form.classList.toggle("is-open", open);
    if (!open) {
      status.textContent = "";
      list.hidden = true;
    }
  }

  function update() {
    const text = input.value;
    if (!text.trim()) {
      setOpen(false);
      return;
    }
    setOpen(true);
    if (!docs.length) status.textContent = "Loading the search…";
    load().then((search) => {
      // Typing went on while loading: the latest input has its own update.
      if (input.value === text && form.classList.contains("is-open")) render(text, search(text));
    }, failed);
  }

  function openFirst() {
    if (!input.value.trim()) return;
    load().then((search) => {
      const found = search(input.value);
      if (found.length) window.location.href = docs[Number(found[0].ref)].url;
      else render(input.value, found);
    }, failed);
  }

  function links() {
    return Array.from(list.querySelectorAll(".site-search-link"));
  }

  input.addEventListener("focus", () => {
    load().catch(() => {}); // a failure is reported when a search is made
    if (input.value.trim()) update();
  });
  input.addEventListener("input", update);
  form.addEventListener("submit", (event) => {
    event.preventDefault();
    openFirst();
  });

  form.addEventListener("keydown", (event) => {
    const all = list.hidden ? [] : links();
    const at = all.indexOf(document.activeElement);
    if (event.key === "Escape" && form.classList.contains("is-open")) {
      // Closing only: the browser's own Escape would also empty the box.
      event.preventDefault();
      setOpen(false);
      input.focus();
    } else if (event.key === "ArrowDown" && all.length) {
      event.preventDefault();
      all[Math.min(at + 1, all.length - 1)].focus();
    } else if (event.key === "ArrowUp" && at >= 0) {
      event.preventDefault();
      (at === 0 ? input : all[at - 1]).focus();
    }
  });

  // The results close when focus leaves the search. A press in the panel keeps focus
  // where it is, so a click on a result is not lost to the panel closing first.
  form.addEventListener("focusout", (event) => {
    if (!form.contains(event.relatedTarget)) setOpen(false);
  });
  panel.addEventListener("mousedown", (event) => event.preventDefault());
  list.addEventListener("click", (event) => {
    if (event.target.closest("a")) setOpen(false);
  });

  // "/" focuses the box, unless the reader is typing somewhere.
  document.addEventListener("keydown", (event) => {
    if (event.key !== "/" || event.ctrlKey || event.metaKey || event.altKey) return;
    const target = event.target;
    if (target.isContentEditable || (target.closest && target.closest("input, textarea, select"))) {
      return;
    }
    event.preventDefault();
    input.focus();
    input.select();
  });
})();
