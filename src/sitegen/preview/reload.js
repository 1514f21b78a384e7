/* sitegen serve --watch: added to each page as it is served (never written into the build).
 * Follows the rebuilds: after a good one the page reloads where the reader was (the scroll position
 * through sessionStorage; a scene's state is in the address, which a reload keeps); after a failed
 * one the errors show over the last good page until a build succeeds. */
(function () {
  "use strict";
  var shown = Number(document.currentScript.getAttribute("data-build"));
  var key = "sitegen-preview-scroll:" + location.pathname;
  var saved = sessionStorage.getItem(key);
  if (saved !== null) {
    sessionStorage.removeItem(key);
    // After the page's own script has run (it scrolls to a scene named in the address).
    window.addEventListener("load", function () { window.scrollTo(0, Number(saved)); });
  }

  var events = new EventSource("/__sitegen/events");
  events.onmessage = function (event) {
    var state = JSON.parse(event.data);
    showErrors(state.errors);
    if (!state.errors.length && state.build !== shown) {
      events.close();
      sessionStorage.setItem(key, String(window.scrollY));
      location.reload();
    }
  };

  function showErrors(errors) {
    var box = document.getElementById("sitegen-build-errors");
    if (!errors.length) {
      if (box) box.remove();
      return;
    }
    if (!box) {
      box = document.createElement("div");
      box.id = "sitegen-build-errors";
      box.setAttribute("role", "alert");
      box.style.cssText = "position:fixed;inset:auto 0 0 0;max-height:60vh;overflow:auto;z-index:2147483647;" +
        "margin:0;padding:1em 1.25em;background:#fff5f5;color:#5c0000;border-top:4px solid #c40000;" +
        "font:14px/1.45 ui-monospace,monospace;box-shadow:0 -4px 16px rgba(0,0,0,.25)";
      document.body.appendChild(box);
    }
    box.textContent = "";
    var title = document.createElement("p");
    title.style.cssText = "margin:0 0 .5em;font-weight:bold";
    title.textContent = "The build failed (" + errors.length + " error" + (errors.length > 1 ? "s" : "") +
      "); this is the last good page. Fix the source: the page reloads when the build succeeds.";
    var list = document.createElement("pre");
    list.style.cssText = "margin:0;white-space:pre-wrap";
    list.textContent = errors.join("\n");
    box.appendChild(title);
    box.appendChild(list);
  }
})();
