/* sitegen search: finds words in the book's prose and captions and links to their sections.
 * The index comes just before this code in the same classic script (window.sitegenSearchIndex):
 * a page opened from disk may run a script but may not fetch a file. sitegen.js loads the script
 * when the search box is first used. */
(function () {
  "use strict";

  var index = window.sitegenSearchIndex, MAX_RESULTS = 12, CONTEXT = 70;
  var input = document.getElementById("search-box");
  var list = document.getElementById("search-results");
  var status = document.getElementById("search-status");
  if (!index || !input || !list) return;

  /* Lower case without accents, every character mapped to exactly one (so that a position in the
   * folded text is the same position in the original), anything but letters and digits a space. */
  function fold(text) {
    var out = "";
    for (var i = 0; i < text.length; i++) {
      var c = text.charAt(i).normalize("NFD").charAt(0).toLowerCase().charAt(0);
      out += /[\p{L}\p{N}]/u.test(c) ? c : " ";
    }
    return out;
  }

  var sections = index.sections.map(function (s) {
    return { page: index.pages[s[0]], id: s[1], title: s[2], text: s[3], inTitle: " " + fold(s[2]), inText: " " + fold(s[3]) };
  });

  /* Every word of the query must begin a word of the section; a word in its heading counts most. */
  function search(query) {
    var words = fold(query).split(" ").filter(Boolean);
    if (!words.length) return [];
    var found = [];
    sections.forEach(function (s, order) {
      var score = 0;
      for (var i = 0; i < words.length; i++) {
        var inTitle = s.inTitle.indexOf(" " + words[i]) >= 0, hits = s.inText.split(" " + words[i]).length - 1;
        if (!inTitle && !hits) return;
        score += (inTitle ? 10 : 0) + Math.min(hits, 5);
      }
      found.push({ section: s, score: score, order: order, first: words[0] });
    });
    found.sort(function (a, b) { return b.score - a.score || a.order - b.order; });
    return found.slice(0, MAX_RESULTS);
  }

  /* The section's text around the first place the query's first word begins, that word marked. */
  function snippet(s, word) {
    var at = s.inText.indexOf(" " + word), item = document.createElement("span");
    if (at < 0) return item;
    var start = Math.max(0, at - CONTEXT), end = Math.min(s.text.length, at + word.length + CONTEXT);
    if (start) start = Math.min(at, s.text.indexOf(" ", start) + 1); // from the start of a word
    if (end < s.text.length) end = Math.max(at + word.length, s.text.lastIndexOf(" ", end)); // to the end of one
    var mark = document.createElement("mark");
    mark.textContent = s.text.slice(at, at + word.length);
    item.append((start ? "…" : "") + s.text.slice(start, at), mark, s.text.slice(at + word.length, end) + (end < s.text.length ? "…" : ""));
    return item;
  }

  function link(result) {
    var s = result.section, a = document.createElement("a"), title = document.createElement("span");
    var where = document.createElement("span"), here = location.pathname.split("/").pop() === s.page[0];
    // on this page, a link to the place (the text's start for the page itself): following it keeps the scenes as they are
    a.href = here ? "#" + (s.id || "main-content") : s.page[0] + (s.id ? "#" + s.id : "");
    title.className = "title";
    title.textContent = s.title;
    where.className = "where";
    where.textContent = s.id ? s.page[1] : "page";
    a.append(title, where, snippet(s, result.first));
    return a;
  }

  function show() {
    var query = input.value.trim(), results = search(query);
    list.textContent = "";
    results.forEach(function (result) {
      var item = document.createElement("li");
      item.appendChild(link(result));
      list.appendChild(item);
    });
    if (query && !results.length) {
      var none = document.createElement("li");
      none.className = "none";
      none.textContent = "No section contains “" + query + "”.";
      list.appendChild(none);
    }
    list.hidden = !query;
    status.textContent = query ? (results.length ? results.length + " sections found" : "nothing found") : "";
  }

  function close() {
    list.hidden = true;
  }

  /* The focus back in the box after the list was closed, without opening it again. */
  var returning = false;
  function backToBox() {
    returning = true;
    input.focus();
    returning = false;
  }

  input.addEventListener("input", show);
  input.addEventListener("focus", function () { if (!returning) show(); });
  input.addEventListener("keydown", function (event) {
    var first = list.querySelector("a");
    if (event.key === "Enter" && first) first.click();
    else if (event.key === "ArrowDown" && first) { event.preventDefault(); first.focus(); }
    else if (event.key === "Escape") { input.value = ""; show(); }
  });
  list.addEventListener("keydown", function (event) {
    var links = Array.prototype.slice.call(list.querySelectorAll("a")), at = links.indexOf(document.activeElement);
    if (event.key === "ArrowDown" || event.key === "ArrowUp") {
      event.preventDefault();
      var next = at + (event.key === "ArrowDown" ? 1 : -1);
      (next < 0 ? input : links[Math.min(next, links.length - 1)]).focus();
    } else if (event.key === "Escape") {
      close();
      backToBox();
    }
  });
  list.addEventListener("click", function (event) { if (event.target.closest("a")) close(); });
  document.addEventListener("click", function (event) { if (!event.target.closest(".search")) close(); });
  show();
})();
