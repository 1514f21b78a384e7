/* sitegen page script: moves scenes by selecting what the build computed. It knows no physics. */
(function () {
  "use strict";

  var MINUS = "\u2212";
  var FRAME_MS = 1000 / 24; // one stop per frame

  /* An integer count of 10^-d units, written as the build writes it: (-2333, 3) -> "−2.333". */
  function formatQuantum(q, d) {
    var digits = String(Math.abs(q));
    while (digits.length < d + 1) digits = "0" + digits;
    var body = d ? digits.slice(0, -d) + "." + digits.slice(-d) : digits;
    return (q < 0 ? MINUS : "") + body;
  }

  /* A value and its unit; "×" and "°" hug the number ("1.00×", "90°"), other units are spaced. */
  function withUnit(text, unit) { return unit ? text + (unit === "\u00d7" || unit === "\u00b0" ? "" : " ") + unit : text; }

  /* A table's row: row-major over its axes' stops, or (marked "sum") their sum. */
  function row(table, stops) {
    var flat = 0;
    for (var k = 0; k < table.axes.length; k++) {
      flat = table.sum ? flat + stops[table.axes[k]] : flat * table.shape[k] + stops[table.axes[k]];
    }
    return flat;
  }

  /* Rounded to a count of 10^-d units by the build's rule, in its steps (compute/quantize.py half_away):
   * to the nearest, a value half-way to 12 significant digits away from zero. */
  function toQuantum(v, d) {
    var x = v * Math.pow(10, d), a = Math.abs(x), w = Math.floor(a);
    w += a - w >= 0.5 - 1e-12 * Math.max(w, 1) ? 1 : 0;
    return x < 0 && w ? -w : w;
  }

  /* Tables stored as differences between neighbours (within each vector), added up. */
  function undelta(rows) {
    if (rows.length && Array.isArray(rows[0])) return rows.map(undelta);
    var out = new Array(rows.length), sum = 0;
    for (var i = 0; i < rows.length; i++) out[i] = sum += rows[i];
    return out;
  }

  /* A table's integers from VLQ text (site/vlq.py: five bits a character, low bits first, the sixth bit
   * set on all but a number's last; the lowest bit the sign, "minus zero" null), differences added up
   * (within each row of a vector's table) if `delta`. */
  var DIGITS = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/", VALUE = new Int8Array(128);
  for (var c = 0; c < 64; c++) VALUE[DIGITS.charCodeAt(c)] = c;

  function unpack(text, delta) {
    var numbers = [], sum = 0, code = 0, scale = 1;
    for (var i = 0; i < text.length; i++) {
      var digit = VALUE[text.charCodeAt(i)];
      code += (digit & 31) * scale;
      if (digit & 32) { scale *= 32; continue; }
      var n = code === 1 ? null : code % 2 ? -(code - 1) / 2 : code / 2;
      numbers.push(delta ? sum += n : n);
      code = 0;
      scale = 1;
    }
    return numbers;
  }

  /* A vector's table: the rows made at their lengths first, then filled (three times faster than slices). */
  function unpackRows(text, lengths, delta) {
    var rows = new Array(lengths.length), r = -1, row = [], j = 0, sum = 0, code = 0, scale = 1;
    var next = function () { // the next row with room, empty ones made on the way
      while (++r < lengths.length && !lengths[r]) rows[r] = [];
      if (r < lengths.length) row = rows[r] = new Array(lengths[r]);
      j = sum = 0;
    };
    next();
    for (var i = 0; i < text.length; i++) {
      var digit = VALUE[text.charCodeAt(i)];
      code += (digit & 31) * scale;
      if (digit & 32) { scale *= 32; continue; }
      var n = code % 2 ? -(code - 1) / 2 : code / 2;
      row[j++] = delta ? sum += n : n;
      if (j === row.length) next();
      code = 0;
      scale = 1;
    }
    return rows;
  }

  function unpackTable(table) {
    var delta = table.enc === "delta";
    return table.len ? unpackRows(table.q, unpack(table.len), delta) : unpack(table.q, delta);
  }

  function short(x) { return String(Math.round(x * 1e6) / 1e6); }

  /* A scene made live: its controls listened to. Its data is read when a control first moves. */
  function Scene(root) {
    this.root = root;
    this.name = root.id.slice(6); // "scene-collision" -> "collision"
    var self = this, moved = function () { self.ready(function () { self.update(); self.remember(); }); };
    var controls = root.querySelectorAll("[data-param]");
    for (var i = 0; i < controls.length; i++) {
      controls[i].addEventListener("input", moved);
      controls[i].addEventListener("change", moved);
    }
    var button = root.querySelector("button[data-animate]");
    if (button) this.animation = new Animation(this, root, button);
    var reset = root.querySelector("button[data-reset]"); // none on a scene without controls
    if (reset) reset.addEventListener("click", function () { self.ready(function () { self.setStops(self.load().defaults); }); });
  }

  /* `fn()` once the scene's data has come (at once if it has): asked for now if it has not been yet. */
  Scene.prototype.ready = function (fn) {
    if (window.sitegenScenes && window.sitegenScenes[this.root.id] !== undefined) fn();
    else askForData(this.root).addEventListener("load", fn);
  };

  /* A scene's data is a classic script of its own (file:// runs those; it blocks fetch), asked for after the
   * first screen (see start), or sooner by a scene the reader reaches for. */
  function askForData(root) {
    return root.querySelector("script.scene-data") || root.appendChild(Object.assign(document.createElement("script"),
      { className: "scene-data", src: root.getAttribute("data-src") }));
  }

  /* Whether a control holds another value than the page was built with (the browser kept the reader's). */
  function restored(root) {
    var inputs = root.querySelectorAll("input");
    for (var i = 0; i < inputs.length; i++) {
      var input = inputs[i];
      if (input.type === "radio" ? input.checked !== input.defaultChecked : input.value !== input.defaultValue) return true;
    }
    return false;
  }

  /* The scene's tables and recipes, decoded when first needed; returns the scene. */
  Scene.prototype.load = function () {
    if (this.data) return this;
    var root = this.root, data = JSON.parse(window.sitegenScenes[root.id]); // kept by its data script
    Object.keys(data.tables).forEach(function (name) {
      var table = data.tables[name];
      if (table.same) data.tables[name] = data.tables[table.same]; // identical tables are stored once
      else if (typeof table.q === "string") table.q = unpackTable(table);
      else if (table.enc === "delta") table.q = undelta(table.q); // too large for VLQ: JSON
    });
    this.data = data;
    var all = function (attr, name) { return root.querySelectorAll("[data-" + attr + '="' + name + '"]'); };
    var each = function (list, attr, key) { return list.map(function (x) { return all(attr, x[key])[0]; }); };
    this.controls = each(data.sliders, "param", "param");
    this.valueTexts = each(data.sliders, "value-of", "param");
    this.readouts = each(data.readouts, "out", "out");
    this.whys = each(data.readouts, "why", "out");
    this.layers = data.layers.map(function (l) { return all("layer", l.name); }); // both figures
    this.defaults = data.sliders.map(function (s, i) { return this.stop(i, true); }, this);
    return this;
  };

  /* A control's stop (`initial`: as built); even sliders hold values, the others indices. */
  Scene.prototype.stop = function (i, initial) {
    var s = this.data.sliders[i], control = this.controls[i], k = 0;
    if (s.kind === "choice") {
      var radios = control.querySelectorAll("input");
      for (var j = 0; j < radios.length; j++) if (initial ? radios[j].defaultChecked : radios[j].checked) k = j;
    } else {
      var v = parseFloat(initial ? control.defaultValue : control.value);
      k = Math.round(s.kind === "list" ? v : (v * Math.pow(10, s.d) - s.lo) / s.step);
    }
    return Math.min(s.count - 1, Math.max(0, k));
  };

  Scene.prototype.setStop = function (i, k) {
    var s = this.data.sliders[i], control = this.controls[i];
    if (s.kind === "choice") control.querySelectorAll("input")[k].checked = true;
    else control.value = String(s.kind === "list" ? k : this.sliderValue(i, k));
  };

  /* Every control to `stops`, the animation paused, the scene redrawn, its link written. */
  Scene.prototype.setStops = function (stops) {
    this.load();
    if (this.animation) this.animation.pause();
    stops.forEach(function (k, i) { this.setStop(i, k); }, this);
    this.update();
    this.remember();
  };

  /* The state as a link, "#collision:m1=2,e=0.5" (controls off their defaults, else the scene's id),
   * replacing the address once the controls rest: Back still leaves the page. */
  Scene.prototype.remember = function () {
    var self = this;
    clearTimeout(this.pending);
    this.pending = setTimeout(function () {
      var pairs = self.stops().map(function (k, i) {
        var s = self.data.sliders[i];
        if (k === self.defaults[i]) return "";
        return s.param + "=" + encodeURIComponent(s.kind === "choice" ? s.texts[k] : short(self.sliderValue(i, k)));
      }).filter(Boolean);
      var hash = pairs.length ? self.name + ":" + pairs.join(",") : self.root.id;
      history.replaceState(history.state, "", "#" + hash);
    }, 300);
  };

  /* The stop of control i that `text` names (an option or a value), else its default. */
  Scene.prototype.findStop = function (i, text) {
    var s = this.data.sliders[i], x = /^-?(\d+\.?\d*|\.\d+)$/.test(text) ? Number(text) : NaN;
    for (var k = 0; k < s.count; k++) {
      if (s.kind === "choice" ? s.texts[k] === text : short(this.sliderValue(i, k)) === short(x)) return k;
    }
    return this.defaults[i];
  };

  Scene.prototype.stops = function () {
    return this.controls.map(function (c, i) { return this.stop(i); }, this);
  };

  /* A control's value as text, as the build wrote it. */
  Scene.prototype.stopText = function (i, k) {
    var s = this.data.sliders[i];
    return s.texts ? s.texts[k] : withUnit(formatQuantum(s.lo + k * s.step, s.d), s.unit);
  };

  /* A control's value at stop k. */
  Scene.prototype.sliderValue = function (i, k) {
    var s = this.data.sliders[i];
    return s.values ? s.values[k] : (s.lo + k * s.step) / Math.pow(10, s.d);
  };

  /* What an output shows: a phrase's index, null (in words), or counts of its last digit (a list for
   * a vector): looked up, or an expression the build proved exact, rounded. */
  Scene.prototype.quantum = function (name, stops) {
    var table = this.data.tables[name];
    if (!table.expr) return table.q[row(table, stops)];
    var v = this.compute(table.expr, stops);
    if (table.labels) return v;
    return Array.isArray(v) ? v.map(function (x) { return toQuantum(x, table.d); }) : toQuantum(v, table.d);
  };

  /* An expression of the build, evaluated as compute/expression.py does: a constant, a control or a
   * table, a polynomial through nodes, a branch, a threshold, a ratio or a logarithm. */
  Scene.prototype.compute = function (e, stops) {
    if ("c" in e) return e.c;
    if ("x" in e) return this.sliderValue(e.x, stops[e.x]);
    if ("t" in e) {
      var table = this.data.tables[e.t], q = table.q[row(table, stops)];
      return table.labels || table.raw ? q : q / Math.pow(10, table.d);
    }
    if ("poly" in e) return this.poly(e, stops);
    if ("sel" in e) return this.compute(e.of[this.compute(e.sel, stops)], stops);
    if ("cut" in e) {
      var v = this.compute(e.cut, stops), above = 0;
      for (var i = 0; i < e.edges.length; i++) if (v > e.edges[i]) above++;
      return e.map[above];
    }
    if ("log10" in e) return e.k * Math.log10(this.compute(e.log10, stops));
    var top = this.compute(e.ratio[0], stops), bottom = this.compute(e.ratio[1], stops);
    return bottom === 0 ? e.zero : e.k * top / bottom;
  };

  /* Lagrange interpolation through each coordinate's nodes (tensor product, row-major values). */
  Scene.prototype.poly = function (e, stops) {
    var weights = [], index = [], total = null, k, j, m;
    for (k = 0; k < e.poly.length; k++) {
      var c = this.compute(e.poly[k], stops), nodes = e.nodes[k], w = [];
      for (j = 0; j < nodes.length; j++) {
        var wj = 1;
        for (m = 0; m < nodes.length; m++) if (m !== j) wj = wj * (c - nodes[m]) / (nodes[j] - nodes[m]);
        w.push(wj);
      }
      weights.push(w);
      index.push(0);
    }
    for (var flat = 0; flat < e.v.length; flat++) {
      var product = 1, v = e.v[flat];
      for (k = 0; k < index.length; k++) product = product * weights[k][index[k]];
      if (Array.isArray(v)) {
        if (!total) total = v.map(function () { return 0; });
        for (j = 0; j < v.length; j++) total[j] = total[j] + v[j] * product;
      } else {
        total = (total || 0) + v * product;
      }
      for (k = index.length - 1; k >= 0; k--) {
        if (++index[k] < e.nodes[k].length) break;
        index[k] = 0;
      }
    }
    return total;
  };

  /* An output as its readout shows it: a phrase, its words where it has no value, or the number to
   * its decimals, or (a table with "forms") written as the entry's form says. */
  Scene.prototype.text = function (name, unit, stops) {
    var table = this.data.tables[name], q = this.quantum(name, stops);
    if (table.labels) return table.labels[q];
    if (q === null) return table.special;
    if (!table.forms) return withUnit(formatQuantum(q, table.d), unit);
    var form = table.forms[table.f[row(table, stops)]];
    return formatQuantum(q, form[0]) + form[1];
  };

  /* A layer reference: a number, [number, ...], ["i", control] or ["o", output]. */
  Scene.prototype.value = function (ref, stops) {
    if (typeof ref === "number" || typeof ref[0] === "number") return ref;
    if (ref[0] === "i") return this.sliderValue(ref[1], stops[ref[1]]);
    var q = this.quantum(ref[1], stops), scale = Math.pow(10, -this.data.tables[ref[1]].d);
    return Array.isArray(q) ? q.map(function (v) { return v * scale; }) : q * scale;
  };

  Scene.prototype.vertices = function (layer, stops) {
    var self = this;
    if (layer.pts) return layer.pts.map(function (xy) { return [self.value(xy[0], stops), self.value(xy[1], stops)]; });
    var xs = this.value(layer.xs, stops), ys = this.value(layer.ys, stops), out = [];
    for (var j = 0; j < Math.min(xs.length, ys.length); j++) out.push([xs[j], ys[j]]);
    return out;
  };

  Scene.prototype.update = function () {
    var stops = this.load().stops(), data = this.data, self = this;
    data.sliders.forEach(function (s, i) {
      var text = self.stopText(i, stops[i]);
      if (s.kind !== "choice") self.controls[i].setAttribute("aria-valuetext", text);
      if (self.valueTexts[i]) self.valueTexts[i].textContent = text;
    });
    data.readouts.forEach(function (r, i) {
      var text = self.text(r.out, r.unit, stops), el = self.readouts[i];
      if (el.textContent !== text) el.textContent = text;
      if (!self.whys[i]) return; // why a value is shown in words: a tooltip, and read out
      el.title = self.whys[i].textContent = self.quantum(r.out, stops) !== null ? "" : r.whyOf ? self.text(r.whyOf, "", stops) : r.why;
    });
    data.layers.forEach(function (layer, i) {
      var elements = self.layers[i];
      if (!elements.length) return;
      if (layer.text) {
        elements[0].textContent = layer.text.map(function (p) {
          return p.o ? self.text(p.o, p.u, stops) : p.i >= 0 ? self.stopText(p.i, stops[p.i]) : p;
        }).join("");
        return;
      }
      var pairs = self.vertices(layer, stops).map(function (p) { return short(p[0]) + "," + short(p[1]); });
      var points = layer.kind === "dots" ? null : pairs.join(" ");
      for (var j = 0; j < elements.length; j++) {
        if (points !== null) { elements[j].setAttribute("points", points); continue; }
        var step = "h" + elements[j].getAttribute("data-dot"); // a dot: a stroke too short to see (render/svg.py)
        elements[j].setAttribute("d", pairs.map(function (xy) { return "M" + xy + step; }).join(" "));
      }
    });
  };

  /* Play/pause of one slider's stops; it pauses when the scene leaves the screen. */
  function Animation(scene, root, button) {
    this.scene = scene;
    this.button = button;
    this.timer = null;
    var self = this;
    button.addEventListener("click", function () { if (self.timer) self.pause(); else scene.ready(function () { self.play(); }); });
    if ("IntersectionObserver" in window) {
      new IntersectionObserver(function (entries) {
        if (!entries[entries.length - 1].isIntersecting) self.pause();
      }).observe(root);
    }
  }

  Animation.prototype.play = function () {
    var self = this, param = this.button.getAttribute("data-animate");
    this.index = this.scene.load().data.sliders.map(function (s) { return s.param; }).indexOf(param);
    this.mark(true);
    this.timer = setInterval(function () { self.step(); }, FRAME_MS);
  };

  Animation.prototype.pause = function () {
    if (!this.timer) return;
    clearInterval(this.timer);
    this.timer = null;
    this.mark(false);
    this.scene.remember();
  };

  /* The button's state; playing silences the readouts (24 updates a second). */
  Animation.prototype.mark = function (playing) {
    var regions = this.scene.root.querySelectorAll("[aria-live]");
    for (var i = 0; i < regions.length; i++) regions[i].setAttribute("aria-live", playing ? "off" : "polite");
    this.button.setAttribute("aria-pressed", String(playing));
    this.button.textContent = playing ? "Pause" : "Play";
  };

  Animation.prototype.step = function () {
    var scene = this.scene;
    scene.setStop(this.index, (scene.stop(this.index) + 1) % scene.data.sliders[this.index].count);
    scene.update();
  };

  /* A display wider than the text scrolls: it is marked (a shadow at each edge that hides more), becomes
   * focusable and says so. (A report's table comes marked: its shadows show only where it overflows.)
   * Overflow depends on font and width: measured once the page is drawn (reading a finished layout costs
   * nothing; at the start it would force one), on resize and when a font arrives. Every box is read, then
   * every box marked, so that marking one does not make the next read lay out. */
  function markScrollers(boxes) {
    var wide = boxes.map(function (box) { return box.scrollWidth > box.clientWidth + 1; });
    boxes.forEach(function (box, i) {
      box.classList.toggle("scrolls", wide[i]);
      var marks = { tabindex: "0", role: "group", "aria-label": "equation, scrolls sideways" };
      for (var name in marks) if (wide[i]) box.setAttribute(name, marks[name]); else box.removeAttribute(name);
    });
  }

  /* A link to a scene's state sets its controls (ignoring unknown names and values) and shows it. */
  function openLink(live) {
    var link = /^#([^:]+):(.*)$/.exec(location.hash), given = {}; // "#collision:m1=2,e=0.5"
    var root = link && document.getElementById("scene-" + link[1]);
    if (!root || !root.hasAttribute("data-scene")) return;
    link[2].split(",").forEach(function (pair) {
      var kv = pair.split("=");
      try { given[kv[0]] = decodeURIComponent(kv[1]); } catch (error) { /* malformed: ignored */ }
    });
    var scene = live(root);
    scene.ready(function () {
      scene.setStops(scene.load().defaults.map(function (k, i) {
        var text = given[scene.data.sliders[i].param];
        return text === undefined ? k : scene.findStop(i, text);
      }));
    });
    // Blocks off the screen hold a guessed height until they near it, so a scene far down would move
    // once they are laid out: every block is laid out now, and the browser keeps the scene in view.
    document.documentElement.classList.add("laid-out");
    root.scrollIntoView();
  }

  /* Search loads its index (a classic script, for file://) when first used. */
  function searchOnDemand() {
    var input = document.querySelector("input[data-index]"), script = document.createElement("script");
    if (input) input.addEventListener("focus", function () {
      script.src = input.getAttribute("data-index");
      document.head.appendChild(script);
    }, { once: true });
  }

  /* Paper shows what a closed <details> holds (a derivation): opened for printing, closed again after. */
  function openDetailsToPrint() {
    var opened = [];
    window.addEventListener("beforeprint", function () {
      var closed = document.querySelectorAll("details:not([open])");
      for (var i = 0; i < closed.length; i++) { closed[i].open = true; opened.push(closed[i]); }
    });
    window.addEventListener("afterprint", function () {
      opened.splice(0).forEach(function (details) { details.open = false; });
    });
  }

  function start() {
    var boxes = [].slice.call(document.querySelectorAll(".equation"));
    var measure = function () { markScrollers(boxes); };
    requestAnimationFrame(function () { setTimeout(measure, 0); }); // after the first frame
    window.addEventListener("resize", measure);
    if (document.fonts) document.fonts.addEventListener("loadingdone", measure);
    // A scene comes alive when the reader first reaches for it (or the browser restored its controls):
    // until then the page shows what the build drew, and loads nothing.
    var elements = [].slice.call(document.querySelectorAll("[data-scene]")), scenes = [];
    var live = function (root) {
      var i = elements.indexOf(root);
      return scenes[i] || (scenes[i] = new Scene(root));
    };
    ["focusin", "pointerdown", "keydown", "input", "change", "click"].forEach(function (type) {
      document.addEventListener(type, function (e) { // capturing: before the control's own listeners
        var root = e.target.closest ? e.target.closest("[data-scene]") : null;
        if (root) live(root);
      }, true);
    });
    // A reader moving by keyboard is taken to blocks far down: lay every block out first (before
    // the Tab moves focus), so the focused one is not pushed off the screen by guessed heights above it.
    document.addEventListener("keydown", function (e) {
      if (e.key === "Tab") document.documentElement.classList.add("laid-out");
    }, true);
    // Back (or a reload) may give the controls the reader's values without an input event: redraw.
    var revive = function () {
      elements.forEach(function (root) { if (restored(root)) live(root).ready(function () { scenes[elements.indexOf(root)].update(); }); });
    };
    revive();
    window.addEventListener("pageshow", revive);
    openLink(live);
    window.addEventListener("hashchange", function () { // a link followed is newer than any state still to be written
      scenes.forEach(function (scene) { clearTimeout(scene.pending); });
      openLink(live);
    });
    searchOnDemand();
    openDetailsToPrint();
    // Every scene's data: at the reader's first scroll, press or key, else a second after the page has loaded
    // (never competing with the first screen); a scene the reader reaches for asks for its own at once.
    var asked = false, allData = function () { if (!asked) elements.forEach(askForData); asked = true; };
    ["scroll", "pointerdown", "keydown"].forEach(function (type) { window.addEventListener(type, allData, { once: true, passive: true }); });
    var later = function () { setTimeout(allData, 1000); };
    if (document.readyState === "complete") later(); else window.addEventListener("load", later);
    var contents = document.getElementById("book-contents"); // the phone's panel closes on a link
    if (contents) contents.addEventListener("click", function (e) { if (e.target.closest("a") && contents.matches(":popover-open")) contents.hidePopover(); });
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
