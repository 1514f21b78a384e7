"""The HTML report's template: one file, inline styles and images, readable from file://."""

TEMPLATE = r"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>Build review: {{ headline }}</title>
<link rel="icon" href="data:,">
<style>
:root { --ink: #1d2430; --muted: #5b6472; --line: #e0e4ea; --bg: #f4f5f7; --card: #fff;
  --new: #1f63b5; --new-bg: #e8f0fa; --new-mark: #bcd5f2; --old: #c8541c; --old-bg: #fcefe7; --old-mark: #f4c7ab;
  --both: #803ca0; --ok: #1e6b3d; --ok-bg: #e2f2e7; }
* { box-sizing: border-box; }
body { margin: 0; background: var(--bg); color: var(--ink);
  font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; }
code, .mono { font-family: ui-monospace, "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 0.9em; }
a { color: var(--new); text-decoration: none; } a:hover { text-decoration: underline; }
.top { background: var(--card); border-bottom: 1px solid var(--line); }
.wrap { max-width: 1440px; margin: 0 auto; padding: 0 32px; }
.top .wrap { padding-top: 22px; padding-bottom: 20px; }
h1 { font-size: 23px; margin: 0; display: flex; align-items: center; gap: 12px; flex-wrap: wrap; }
.pill { font-size: 13px; font-weight: 600; padding: 3px 11px; border-radius: 999px; background: var(--old-bg);
  color: #8a3510; }
.pill.same { background: var(--ok-bg); color: var(--ok); }
.versions { margin: 8px 0 0; color: var(--muted); }
.versions code { color: var(--ink); background: var(--bg); padding: 1px 6px; border-radius: 4px; }
.stats { display: flex; gap: 10px; flex-wrap: wrap; margin-top: 16px; }
.stat { background: var(--bg); border-radius: 8px; padding: 7px 14px; min-width: 104px; }
.stat b { display: block; font-size: 20px; line-height: 1.25; }
.stat b small { font-size: 13px; font-weight: 400; color: var(--muted); }
.stat span { color: var(--muted); font-size: 13px; }
.toc { margin: 18px 0 0; padding: 0; list-style: none; display: flex; flex-wrap: wrap; gap: 6px 8px; }
.toc a { display: inline-block; border: 1px solid var(--line); border-radius: 6px; padding: 2px 9px;
  background: var(--card); font-size: 13.5px; }
main.wrap { padding-top: 8px; padding-bottom: 64px; }
h2 { font-size: 19px; margin: 30px 0 4px; display: flex; gap: 10px; align-items: baseline; flex-wrap: wrap; }
h2 .file { font-weight: 400; color: var(--muted); font-size: 14px; }
.card { background: var(--card); border: 1px solid var(--line); border-radius: 10px; padding: 18px 22px 20px;
  margin: 14px 0;
  box-shadow: 0 1px 2px rgba(20, 30, 50, 0.04); }
.card > header { display: flex; align-items: baseline; gap: 8px; flex-wrap: wrap; }
h3 { font-size: 17px; margin: 0 6px 0 0; }
h4 { font-size: 13px; text-transform: uppercase; letter-spacing: 0.06em; color: var(--muted); margin: 20px 0 8px; }
.tag { font-size: 12.5px; padding: 1px 9px; border-radius: 999px; background: var(--bg); color: var(--muted);
  white-space: nowrap; }
.tag.hot { background: var(--old-bg); color: #8a3510; }
.figs { display: grid; grid-template-columns: repeat(3, minmax(0, 1fr)); gap: 14px; }
.figs figure { margin: 0; }
.figs figcaption { font-size: 12px; font-weight: 600; letter-spacing: 0.06em; text-transform: uppercase;
  color: var(--muted); margin: 0 0 5px; }
.figs img { display: block; width: 100%; height: auto; background: #fff; border: 1px solid var(--line);
  border-radius: 6px; }
.zoom { display: flex; flex-wrap: wrap; gap: 14px; margin-top: 14px; }
.zoom figure { margin: 0; max-width: 100%; }
.zoom figcaption { font-size: 12px; font-weight: 600; letter-spacing: 0.06em; text-transform: uppercase;
  color: var(--muted); margin: 0 0 5px; }
.zoom img { display: block; max-width: 100%; height: auto; border: 1px solid var(--line); border-radius: 6px;
  background: #fff; }
.measure { margin: 10px 0 0; }
.measure b { font-variant-numeric: tabular-nums; }
.notes { margin: 4px 0 0; color: var(--muted); font-size: 14px; }
.key { display: inline-flex; align-items: center; gap: 5px; margin-right: 14px; white-space: nowrap; }
.key i { width: 11px; height: 11px; border-radius: 2px; display: inline-block; }
table.numbers { width: 100%; border-collapse: collapse; font-size: 14px; }
.numbers th { text-align: left; font-weight: 600; font-size: 12.5px; color: var(--muted);
  border-bottom: 2px solid var(--line); padding: 6px 10px 6px 0; }
.numbers td { border-bottom: 1px solid var(--line); padding: 7px 10px 7px 0; vertical-align: top; }
.numbers tr:last-child td { border-bottom: 0; }
.numbers .out { font-weight: 600; white-space: nowrap; }
.numbers .n { font-variant-numeric: tabular-nums; white-space: nowrap; }
.numbers .size { font-weight: 600; font-variant-numeric: tabular-nums; }
.numbers .from { color: var(--muted); font-size: 13px; }
.numbers .from .mono { color: var(--ink); }
.bar { display: block; height: 4px; width: 90px; background: var(--bg); border-radius: 2px; margin-top: 4px;
  overflow: hidden; }
.bar i { display: block; height: 100%; background: var(--old); }
.diff { border: 1px solid var(--line); border-radius: 6px; overflow: hidden; font-size: 13.5px; line-height: 1.45; }
.diff div { padding: 2px 12px 2px 30px; position: relative; white-space: pre-wrap; overflow-wrap: anywhere; }
.diff div::before { position: absolute; left: 11px; color: var(--muted); font-family: ui-monospace,
  "DejaVu Sans Mono", monospace; }
.diff .del { background: var(--old-bg); } .diff .del::before { content: "−"; color: var(--old); }
.diff .add { background: var(--new-bg); } .diff .add::before { content: "+"; color: var(--new); }
.diff .ctx { color: var(--muted); }
.diff .gap { background: var(--bg); color: var(--muted); font-size: 12px; padding: 0 12px; }
.diff .del mark { background: var(--old-mark); color: inherit; border-radius: 2px; }
.diff .add mark { background: var(--new-mark); color: inherit; border-radius: 2px; }
pre.markup { margin: 0; padding: 10px 12px; background: var(--bg); border-radius: 6px; overflow: auto;
  font-size: 12.5px; }
ul.plain { margin: 0; padding-left: 18px; }
.empty { background: var(--card); border: 1px dashed var(--line); border-radius: 10px; padding: 28px;
  text-align: center; color: var(--muted); margin-top: 24px; }
footer { color: var(--muted); font-size: 13px; margin-top: 36px; }
@media (max-width: 900px) { .figs { grid-template-columns: 1fr; } .wrap { padding: 0 14px; } }
</style>
</head>
<body>
{% macro diff(lines) %}
<div class="diff">
{% for line in lines[:max_lines] %}
<div class="{{ {'-': 'del', '+': 'add', ' ': 'ctx', '…': 'gap'}[line.kind] }}">{% if line.kind == '…' %}…{% endif %}{% for piece, hot in line.runs %}{% if hot and line.kind != ' ' and line.runs|length > 1 %}<mark>{{ piece }}</mark>{% else %}{{ piece }}{% endif %}{% endfor %}</div>
{% endfor %}
{% if lines|length > max_lines %}<div class="gap">… {{ lines|length - max_lines }} more lines</div>{% endif %}
</div>
{% endmacro %}
<header class="top"><div class="wrap">
<h1>Build review <span class="pill{% if not review.changed %} same{% endif %}">{{ headline }}</span></h1>
<p class="versions">old <code>{{ review.old_label }}</code> → new <code>{{ review.new_label }}</code></p>
<div class="stats">
{% for name, changed, total in stats %}
<div class="stat"><b>{{ changed }}{% if total is not none %} <small>of {{ total }}</small>{% endif %}</b><span>{{
  name }} changed</span></div>
{% endfor %}
</div>
{% if review.scenes() or review.pages %}
<ul class="toc">
{% for page in review.pages %}
{% if page.text or page.markup or page.status != 'changed' %}<li><a href="#page-{{ page.name }}">{{
  page.name }}: text</a></li>{% endif %}
{% for scene in page.scenes %}<li><a href="#{{ anchor(scene) }}">{{ scene.id }}</a></li>{% endfor %}
{% endfor %}
{% if review.files %}<li><a href="#files">other files</a></li>{% endif %}
</ul>
{% endif %}
</div></header>
<main class="wrap">
{% if not review.changed %}
<div class="empty">The two builds are byte-identical: {{ review.page_count }} pages, {{ review.scene_count }} scenes,
  every file the same.</div>
{% endif %}
{% if review.render_note %}
<p class="empty">Figures were not rendered to pixels: {{ review.render_note }}. Old and new are shown as SVG;
  no difference image.</p>
{% endif %}
{% for page in review.pages %}
<h2 id="page-{{ page.name }}">{{ page.title }} <span class="file">{{
  page.name }}{% if page.status != 'changed' %} · page {{ page.status }}{% endif %}</span></h2>
{% if page.text %}
<section class="card"><header><h3>Text outside the scenes</h3><span class="tag">{{ page.text|selectattr('kind', 'in',
  '+-')|list|length }} changed lines</span></header>
<h4>Changed text</h4>
{{ diff(page.text) }}
</section>
{% elif page.markup %}
<section class="card"><header><h3>Markup outside the scenes</h3><span class="tag">no visible text changed</span></header>
<pre class="markup">{{ page.markup|join('\n') }}</pre>
</section>
{% endif %}
{% for scene in page.scenes %}
<article class="card" id="{{ anchor(scene) }}">
<header><h3>Scene <code>{{ scene.id }}</code></h3>
<span class="tag">model {{ scene.model }}</span>
{% if scene.status != 'changed' %}<span class="tag hot">scene {{ scene.status }}</span>{% else %}
{% if scene.figure %}<span class="tag hot">figure changed</span>{% endif %}
{% if scene.tables %}<span class="tag hot">{{ scene.tables|length }} of {{
  scene.table_count }} tables changed</span>{% endif %}
{% if scene.panel %}<span class="tag hot">readouts or controls changed</span>{% endif %}
{% endif %}
</header>
{% set fig = scene.figure %}
{% if fig %}
<h4>Figure at the default slider values</h4>
{% if fig.pixels %}
<div class="figs">
<figure><figcaption>Old</figcaption><img alt="old figure" src="{{ png(fig.pixels.old_png) }}"></figure>
<figure><figcaption>New</figcaption><img alt="new figure" src="{{ png(fig.pixels.new_png) }}"></figure>
<figure><figcaption>Difference</figcaption><img alt="pixels that differ" src="{{ png(fig.pixels.diff_png) }}"></figure>
</div>
{% if fig.pixels.zoom %}
<div class="zoom">
<figure><figcaption>Old,
  around the change (2×)</figcaption><img alt="old figure around the change" src="{{ png(fig.pixels.zoom[0]) }}"></figure>
<figure><figcaption>New,
  around the change (2×)</figcaption><img alt="new figure around the change" src="{{ png(fig.pixels.zoom[1]) }}"></figure>
<figure><figcaption>Difference,
  around the change</figcaption><img alt="pixels that differ, around the change" src="{{ png(fig.pixels.zoom[2]) }}"></figure>
</div>
{% endif %}
<p class="measure">{% if fig.pixels.changed %}<b>{{ percent(fig.pixels.fraction) }}</b> of the figure differs — {{
  '{:,}'.format(fig.pixels.changed) }} px at {{ scale }}×, within x {{ '%g'|format(fig.pixels.box[0]) }}–{{
    '%g'|format(fig.pixels.box[2]) }}, y {{ '%g'|format(fig.pixels.box[1]) }}–{{ '%g'|format(fig.pixels.box[3])
      }} pt.{% else %}No pixel differs: the SVG text changed below the resolution.{% endif %}</p>
<p class="notes">{% for note in figure_notes(scene) %}{{ note }}{% if not loop.last %} · {% endif %}{% endfor %}</p>
<p class="notes"><span class="key"><i style="background: var(--new)"></i>only in new</span><span class="key"><i style="background: var(--old)"></i>only in old</span><span class="key"><i style="background: var(--both)"></i>colour changed</span></p>
{% else %}
<div class="figs">
<figure><figcaption>Old</figcaption>{% if fig.old_svg %}<img alt="old figure" src="{{ svg(fig.old_svg) }}">{% else %}<p class="notes">none: the scene is new</p>{% endif %}</figure>
<figure><figcaption>New</figcaption>{% if fig.new_svg %}<img alt="new figure" src="{{ svg(fig.new_svg) }}">{% else %}<p class="notes">none: the scene was removed</p>{% endif %}</figure>
</div>
<p class="notes">{% for note in figure_notes(scene) %}{{ note }}{% if not loop.last %} · {% endif %}{% endfor %}</p>
{% endif %}
{% endif %}
{% if scene.tables %}
<h4>Numbers, at every stop of the sliders</h4>
<table class="numbers">
<thead><tr><th>output</th><th>stops changed</th><th>largest change</th><th>largest relative change</th><th>where</th></tr></thead>
<tbody>
{% for t in scene.tables %}
<tr><td class="out"><code>{{ t.output }}</code>{% if t.unit %} <span class="from">{{ t.unit }}</span>{% endif %}</td>
{% if t.status != 'changed' %}<td colspan="4">output {{ t.status }}{% for note in t.notes %} · {{
  note }}{% endfor %}</td>
{% else %}
<td class="n">{{ '{:,}'.format(t.changed) }} of {{ '{:,}'.format(t.stops)
  }}<span class="bar"><i style="width: {{ (100 * t.changed / t.stops if t.stops else 0)|round(1) }}%"></i></span></td>
<td>{% if t.largest_abs %}{% if t.largest_abs.size %}<span class="size">{{
  t.largest_abs.size }}</span><br>{% endif %}<span class="from"><span class="mono">{{ t.largest_abs.old }} → {{
    t.largest_abs.new }}</span><br>at {{ t.largest_abs.where or 'the only stop' }}</span>{% endif %}</td>
<td>{% if t.largest_rel %}<span class="size">{{
  t.largest_rel.size }}</span><br><span class="from"><span class="mono">{{ t.largest_rel.old }} → {{
    t.largest_rel.new }}</span><br>at {{ t.largest_rel.where or 'the only stop' }}</span>{% endif %}</td>
<td>{{ t.where }}{% for note in t.notes %}<br><span class="from">{{ note }}</span>{% endfor %}</td>
{% endif %}
</tr>
{% endfor %}
</tbody>
</table>
{% endif %}
{% if scene.controls %}
<h4>{% if scene.status == 'changed' %}Controls and data{% else %}Tables{% endif %}</h4>
<ul class="plain">{% for note in scene.controls %}<li>{{ note }}</li>{% endfor %}</ul>
{% endif %}
{% if scene.panel %}
<h4>Controls, readouts at the defaults, caption</h4>
{{ diff(scene.panel) }}
{% endif %}
{% if scene.markup %}
<h4>Markup</h4>
<pre class="markup">{{ scene.markup|join('\n') }}</pre>
{% endif %}
</article>
{% endfor %}
{% endfor %}
{% if review.files %}
<h2 id="files">Other files</h2>
<section class="card">
<table class="numbers"><thead><tr><th>file</th><th>status</th><th>bytes</th></tr></thead><tbody>
{% for f in review.files %}<tr><td class="out"><code>{{ f.name }}</code></td><td>{{ f.status }}</td><td class="n">{{
  '{:,}'.format(f.old_size) }} → {{ '{:,}'.format(f.new_size) }}</td></tr>
{% endfor %}</tbody></table>
</section>
{% endif %}
<footer>Made by <code>sitegen review</code>. Figures rendered by Chromium at {{
  scale }} px per point and compared pixel by pixel with Pillow;
numbers decoded from the scenes' inline tables and compared at every slider stop both builds share.
Only what changed is listed.</footer>
</main>
</body>
</html>
"""
