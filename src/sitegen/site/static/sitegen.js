/* sitegen page script: moves scenes by selecting precomputed results.
 * It knows sliders, tables and layers, and nothing of physics: every number it shows was
 * computed and rounded at build time; here it is only looked up and written out. */
(function () {
  "use strict";

  var MINUS = "\u2212";

  /* An integer count of 10^-d units, written as the build writes it: (-2333, 3) -> "−2.333". */
  function formatQuantum(q, d) {
    var digits = String(Math.abs(q));
    while (digits.length < d + 1) digits = "0" + digits;
    var body = d ? digits.slice(0, -d) + "." + digits.slice(-d) : digits;
    return (q < 0 ? MINUS : "") + body;
  }

  function withUnit(text, unit) {
    return unit ? text + " " + unit : text;
  }

  /* The entry of a table at the current slider stops (row-major over the table's own axes). */
  function lookup(table, stops) {
    var flat = 0;
    for (var k = 0; k < table.axes.length; k++) flat = flat * table.shape[k] + stops[table.axes[k]];
    return table.q[flat];
  }

  function Scene(root) {
    var data = JSON.parse(root.querySelector("script.scene-data").textContent);
    Object.keys(data.tables).forEach(function (name) {
      var table = data.tables[name];
      if (table.same) data.tables[name] = data.tables[table.same];  // identical tables are stored once
    });
    this.data = data;
    this.inputs = data.sliders.map(function (s) {
      return root.querySelector('input[data-param="' + s.param + '"]');
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
    this.inputs.forEach(function (input) {
      input.addEventListener("input", update);
    });
    this.update();
  }

  /* The stop index of every slider, from the inputs' current values. */
  Scene.prototype.stops = function () {
    var sliders = this.data.sliders;
    return this.inputs.map(function (input, i) {
      var s = sliders[i], scale = Math.pow(10, s.d);
      var k = Math.round((parseFloat(input.value) * scale - s.lo) / s.step);
      return Math.min(s.count - 1, Math.max(0, k));
    });
  };

  Scene.prototype.value = function (ref, stops) {
    if (typeof ref === "number") return ref;
    if (ref[0] === "i") {
      var s = this.data.sliders[ref[1]];
      return (s.lo + stops[ref[1]] * s.step) / Math.pow(10, s.d);
    }
    var table = this.data.tables[ref[1]];
    return lookup(table, stops) / Math.pow(10, table.d);
  };

  Scene.prototype.update = function () {
    var stops = this.stops(), data = this.data, self = this;
    data.sliders.forEach(function (s, i) {
      var text = withUnit(formatQuantum(s.lo + stops[i] * s.step, s.d), s.unit);
      self.inputs[i].setAttribute("aria-valuetext", text);
      if (self.valueTexts[i]) self.valueTexts[i].textContent = text;
    });
    data.readouts.forEach(function (r, i) {
      var table = data.tables[r.out], q = lookup(table, stops);
      self.readouts[i].textContent = table.labels ? table.labels[q] : withUnit(formatQuantum(q, table.d), r.unit);
    });
    data.layers.forEach(function (layer, i) {
      var points = layer.pts.map(function (xy) {
        return round6(self.value(xy[0], stops)) + "," + round6(self.value(xy[1], stops));
      });
      if (self.layers[i]) self.layers[i].setAttribute("points", points.join(" "));
    });
  };

  function round6(x) {
    return String(Math.round(x * 1e6) / 1e6);
  }

  function start() {
    var scenes = document.querySelectorAll("[data-scene]");
    for (var i = 0; i < scenes.length; i++) new Scene(scenes[i]);
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
