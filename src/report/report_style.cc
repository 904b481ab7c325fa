#include "report/report_style.h"

namespace inertest::report {

std::string_view report_css() {
  return R"css(:root { --ink: #1d2330; --muted: #5b6474; --rule: #d5d9e0; --band: #f3f5f8;
  --pass: #1a7f37; --fail: #c62828; --accent: #1f4e79; }
* { box-sizing: border-box; }
html { -webkit-text-size-adjust: 100%; }
body { margin: 0 auto; max-width: 980px; padding: 24px 28px 48px; color: var(--ink); background: #ffffff;
  font-family: 'DejaVu Sans', 'Noto Sans CJK SC', 'Noto Sans SC', 'WenQuanYi Micro Hei', Arial, sans-serif;
  font-size: 14px; line-height: 1.45; }
h1 { font-size: 26px; margin: 2px 0 12px; color: var(--accent); }
h2 { font-size: 19px; margin: 28px 0 10px; padding-bottom: 4px; border-bottom: 2px solid var(--accent); }
h3 { font-size: 15px; margin: 16px 0 6px; }
.kicker { margin: 0; color: var(--muted); text-transform: uppercase; letter-spacing: 0.08em; font-size: 12px; }
.overall { display: inline-block; margin: 4px 0 14px; padding: 8px 16px; border-radius: 4px; color: #ffffff;
  font-size: 16px; }
.overall strong { font-size: 18px; margin-left: 8px; }
.verdict-pass { background: var(--pass); }
.verdict-fail { background: var(--fail); }
.verdict-none { background: var(--muted); }
.facts { display: flex; flex-wrap: wrap; gap: 16px; }
.facts table { flex: 1 1 280px; width: auto; }
.facts caption { text-align: left; font-weight: bold; padding: 4px 0; color: var(--accent); }
.facts th { width: 46%; color: var(--muted); font-weight: normal; }
table { border-collapse: collapse; width: 100%; margin: 6px 0 12px; }
th, td { text-align: left; padding: 4px 8px; border-bottom: 1px solid var(--rule); vertical-align: top; }
thead th { background: var(--band); border-bottom: 2px solid var(--rule); }
tr.group th { background: #ffffff; color: var(--accent); padding-top: 10px; border-bottom: 1px solid var(--accent); }
.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.verdict-cell { font-weight: bold; white-space: nowrap; }
td.pass { color: var(--pass); }
td.fail { color: #ffffff; background: var(--fail); }
tfoot th { text-align: right; }
table.rows { display: block; overflow-x: auto; font-size: 13px; }
tr.more td { color: var(--muted); font-style: italic; }
.contents ol { margin: 4px 0; padding-left: 22px; columns: 2; }
.contents a { color: var(--accent); text-decoration: none; }
.kind { margin: -6px 0 8px; color: var(--muted); }
.clause { font-weight: bold; }
code.digest { font-size: 11px; word-break: break-all; }
.method p { margin: 4px 0; }
.warnings { border-left: 4px solid #e0a800; background: #fff8e1; padding: 4px 12px; margin: 10px 0; }
.warnings h3 { margin: 4px 0; }
figure { margin: 18px 0; }
figcaption { color: var(--muted); font-size: 13px; margin-top: 4px; }
svg.plot { display: block; max-width: 100%; height: auto; }
footer { margin-top: 32px; padding-top: 8px; border-top: 1px solid var(--rule); color: var(--muted);
  font-size: 12px; }
@media print {
  @page { size: A4; margin: 14mm 12mm; }
  body { max-width: none; padding: 0; font-size: 10pt; }
  h1 { font-size: 20pt; }
  h2 { font-size: 14pt; }
  .contents { display: none; }
  section.procedure, section.truth { break-before: page; }
  /* A history or fleet page's figures are short: each kept whole, not each on a page of its own. */
  body.archive section.procedure { break-before: auto; break-inside: avoid; }
  table.rows { display: table; overflow: visible; font-size: 8pt; }
  h2, h3 { break-after: avoid; }
  figure, tr, .facts table, .overall { break-inside: avoid; }
  thead { display: table-header-group; }
  .overall, td.fail, thead th { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
}
)css";
}

}  // namespace inertest::report
