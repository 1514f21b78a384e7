/* sitegen page script: moves scenes by selecting precomputed results.
 * It knows controls, tables and layers, and nothing of physics: every number it shows was
 * computed and rounded when the book was built; here it is only looked up and written out. */
(function () {
  "use strict";

  var MINUS = "\u2212";
  var FRAME_MS = 1000 / 24; // animation: one slider stop per frame

  /* An integer count of 10^-d units, written as the build writes it: (-2333, 3) -> "−2.333". */
  function formatQuantum(q, d) {
    var digits = String(Math.abs(q));
    while (digits.length < d + 1) digits = "0" + digits;
    var body = d ? digits.slice(0, -d) + "." + digits.slice(-d) : digits;
    return (q < 0 ? MINUS : "") + body;
  }

  /* A value and its unit; "×" and "°" hug the number ("1.00×", "90°"), other units are spaced. */
  function withUnit(text, unit) {
    return unit ? text + (unit === "\u00d7" || unit === "\u00b0" ? "" : " ") + unit : text;
  }

  /* The entry of a table at the current stops (row-major over the table's own axes). */
  function lookup(table, stops) {
    var flat = 0;
    for (var k = 0; k < table.axes.length; k++) flat = flat * table.shape[k] + stops[table.axes[k]];
    return table.q[flat];
  }

  /* Tables may be stored as differences between neighbours (within each vector): add them up. */
  function undelta(rows) {
    if (rows.length && Array.isArray(rows[0])) return rows.map(undelta);
    var out = new Array(rows.length), sum = 0;
    for (var i = 0; i < rows.length; i++) out[i] = sum += rows[i];
    return out;
  }

  function short(x) {
    return String(Math.round(x * 1e6) / 1e6);
  }

  function Scene(root) {
    var data = JSON.parse(root.querySelector("script.scene-data").textContent);
    Object.keys(data.tables).forEach(function (name) {
      var table = data.tables[name];
      if (table.same) data.tables[name] = data.tables[table.same]; // identical tables are stored once
      else if (table.enc === "delta") table.q = undelta(table.q);
    });
    this.data = data;
    this.controls = data.sliders.map(function (s) {
      return root.querySelector('[data-param="' + s.param + '"]');
    });
    this.valueTexts = data.sliders.map(function (s) {
      return root.querySelector('output[data-value-of="' + s.param + '"]');
    });
    this.readouts = data.readouts.map(function (r) {
      return root.querySelector('[data-out="' + r.out + '"]');
    });
    this.layers = data.layers.map(function (l) {
      return root.querySelector('[data-layer="' + l.name + '"]');
    });
    var update = this.update.bind(this);
    this.controls.forEach(function (control) {
      control.addEventListener("input", update);
      control.addEventListener("change", update);
    });
    var button = root.querySelector("button[data-animate]");
    if (button) this.animation = new Animation(this, root, button);
    this.update();
  }

  /* The stop index of one control: evenly spaced sliders carry values, listed ones indices. */
  Scene.prototype.stop = function (i) {
    var s = this.data.sliders[i], control = this.controls[i], k;
    if (s.kind === "choice") {
      var checked = control.querySelector("input:checked");
      k = checked ? parseInt(checked.value, 10) : 0;
    } else if (s.kind === "list") {
      k = Math.round(parseFloat(control.value));
    } else {
      k = Math.round((parseFloat(control.value) * Math.pow(10, s.d) - s.lo) / s.step);
    }
    return Math.min(s.count - 1, Math.max(0, k));
  };

  Scene.prototype.stops = function () {
    var stops = [];
    for (var i = 0; i < this.controls.length; i++) stops.push(this.stop(i));
    return stops;
  };

  /* A control's value as text, as the build wrote it next to the control. */
  Scene.prototype.stopText = function (i, k) {
    var s = this.data.sliders[i];
    return s.texts ? s.texts[k] : withUnit(formatQuantum(s.lo + k * s.step, s.d), s.unit);
  };

  /* A layer reference: a number, [number, ...], ["i", control] or ["o", table] (a number or a list). */
  Scene.prototype.value = function (ref, stops) {
    if (typeof ref === "number") return ref;
    if (typeof ref[0] === "number") return ref;
    if (ref[0] === "i") {
      var s = this.data.sliders[ref[1]], k = stops[ref[1]];
      return s.values ? s.values[k] : (s.lo + k * s.step) / Math.pow(10, s.d);
    }
    var table = this.data.tables[ref[1]], q = lookup(table, stops), scale = Math.pow(10, -table.d);
    return Array.isArray(q) ? q.map(function (v) { return v * scale; }) : q * scale;
  };

  Scene.prototype.vertices = function (layer, stops) {
    var self = this;
    if (layer.pts) {
      return layer.pts.map(function (xy) {
        return [self.value(xy[0], stops), self.value(xy[1], stops)];
      });
    }
    var xs = this.value(layer.xs, stops), ys = this.value(layer.ys, stops), out = [];
    for (var j = 0; j < Math.min(xs.length, ys.length); j++) out.push([xs[j], ys[j]]);
    return out;
  };

  Scene.prototype.update = function () {
    var stops = this.stops(), data = this.data, self = this;
    data.sliders.forEach(function (s, i) {
      var text = self.stopText(i, stops[i]);
      if (s.kind !== "choice") self.controls[i].setAttribute("aria-valuetext", text);
      if (self.valueTexts[i]) self.valueTexts[i].textContent = text;
    });
    data.readouts.forEach(function (r, i) {
      var table = data.tables[r.out], q = lookup(table, stops), text;
      if (table.labels) text = table.labels[q];
      else if (q === null) text = table.special;
      else text = withUnit(formatQuantum(q, table.d), r.unit);
      if (self.readouts[i].textContent !== text) self.readouts[i].textContent = text;
    });
    data.layers.forEach(function (layer, i) {
      var element = self.layers[i];
      if (!element) return;
      var vertices = self.vertices(layer, stops);
      if (layer.kind === "dots") {
        element.setAttribute("d", vertices.map(function (p) { return "M" + short(p[0]) + "," + short(p[1]) + "h0"; }).join(" "));
      } else {
        element.setAttribute("points", vertices.map(function (p) { return short(p[0]) + "," + short(p[1]); }).join(" "));
      }
    });
  };

  /* Play/pause for a scene that animates one slider; it pauses when the scene leaves the screen. */
  function Animation(scene, root, button) {
    this.scene = scene;
    this.root = root;
    this.button = button;
    this.index = scene.data.sliders.map(function (s) { return s.param; }).indexOf(button.getAttribute("data-animate"));
    this.timer = null;
    var self = this;
    button.addEventListener("click", function () {
      if (self.timer) self.pause();
      else self.play();
    });
    if ("IntersectionObserver" in window) {
      new IntersectionObserver(function (entries) {
        if (!entries[entries.length - 1].isIntersecting) self.pause();
      }).observe(root);
    }
  }

  Animation.prototype.play = function () {
    var self = this;
    this.setAnnouncements("off"); // 24 updates a second would drown a screen reader
    this.button.setAttribute("aria-pressed", "true");
    this.button.textContent = "Pause";
    this.timer = setInterval(function () { self.step(); }, FRAME_MS);
  };

  Animation.prototype.pause = function () {
    if (!this.timer) return;
    clearInterval(this.timer);
    this.timer = null;
    this.setAnnouncements("polite");
    this.button.setAttribute("aria-pressed", "false");
    this.button.textContent = "Play";
  };

  Animation.prototype.setAnnouncements = function (mode) {
    var regions = this.root.querySelectorAll("[aria-live]");
    for (var i = 0; i < regions.length; i++) regions[i].setAttribute("aria-live", mode);
  };

  Animation.prototype.step = function () {
    var s = this.scene.data.sliders[this.index], control = this.scene.controls[this.index];
    var k = (this.scene.stop(this.index) + 1) % s.count;
    control.value = s.kind === "list" ? String(k) : String((s.lo + k * s.step) / Math.pow(10, s.d));
    this.scene.update();
  };

  function start() {
    var elements = document.querySelectorAll("[data-scene]"), scenes = [];
    for (var i = 0; i < elements.length; i++) scenes.push(new Scene(elements[i]));
    // Going Back restores the controls' positions after load without an input event: redraw.
    window.addEventListener("pageshow", function () {
      scenes.forEach(function (scene) { scene.update(); });
    });
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
