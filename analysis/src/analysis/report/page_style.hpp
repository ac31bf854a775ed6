// The page's stylesheet, screen and print (kept apart from the page builder
// so the layout can be read on its own).
#pragma once

namespace rollsense::report {

inline constexpr const char* kPageStyle = R"css(
:root { color-scheme: light; }
body { font-family: "DejaVu Sans", "Helvetica Neue", Arial, sans-serif; color: #111; background: #fff;
       max-width: 1100px; margin: 0 auto; padding: 24px 28px 60px; line-height: 1.45; }
h1 { font-size: 1.7em; margin: 0 0 0.2em; }
h2 { font-size: 1.25em; margin: 1.8em 0 0.5em; border-bottom: 2px solid #1f5fa8; padding-bottom: 0.15em; }
p.lead { color: #333; margin-top: 0; }
p.note, figcaption { color: #444; font-size: 0.92em; }
figure { margin: 1em 0 1.6em; }
figure svg { max-width: 100%; height: auto; display: block; }
table.numbers { border-collapse: collapse; margin: 0.5em 0 1em; font-size: 0.93em; }
table.numbers th, table.numbers td { border: 1px solid #ccc; padding: 4px 9px; text-align: left; vertical-align: top; }
table.numbers thead th { background: #eef3fa; }
table.numbers tbody th { background: #f7f7f7; font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tr.optimistic td { background: #fff6e5; }
.headline { font-size: 1.15em; background: #f3f7fc; border-left: 4px solid #1f5fa8; padding: 10px 14px; }
code { font-size: 0.9em; word-break: break-all; }
nav ol { columns: 2; font-size: 0.95em; }
@media print {
  @page { size: A4; margin: 14mm; }
  body { max-width: none; padding: 0; font-size: 10pt; }
  nav { display: none; }
  h2 { break-after: avoid; page-break-after: avoid; }
  figure, table { break-inside: avoid; page-break-inside: avoid; }
  * { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
  a { color: inherit; text-decoration: none; }
}
)css";

}  // namespace rollsense::report
