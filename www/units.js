// The page's units: every length the page shows or takes, in millimetres or in inches (the
// header's "Show in"; kept in the browser for the next visit). The job, the engine and the
// files stay in mm: a field shows its value in the page's units and reads back what is typed
// into mm, a read-out says its figure in them. Which fields hold lengths the labels tell:
// "(mm …" a length, "(mm/min …" a feed; their words follow the units. The program's own
// units (G20/G21) are the controller's setting.
const INCH = 25.4;
const KEY = 'swarf.pageUnits';

let unit = (() => {
  try { return localStorage.getItem(KEY) === 'inch' ? 'inch' : 'mm'; } catch { return 'mm'; }
})();

export const inInches = () => unit === 'inch';
export const pageUnits = () => unit;

export function setPageUnits(u) {
  unit = u === 'inch' ? 'inch' : 'mm';
  try { localStorage.setItem(KEY, unit); } catch { /* private mode: for this visit */ }
  document.body.dataset.units = unit;
  relabel();
}

// The short name of a length, a feed, an area and a volume in the page's units.
export const lengthUnit = () => (inInches() ? 'in' : 'mm');
export const feedUnit = () => (inInches() ? 'in/min' : 'mm/min');

// A length in mm as the page's number of its units, and back.
export const toPage = (mm) => (inInches() ? mm / INCH : mm);
export const fromPage = (v) => (inInches() ? v * INCH : v);

// A field's value in the page's units, as a machinist types it: a length to 4 decimals (a
// tenth of a thousandth in inches, a tenth of a micron in mm), a feed (`kind` 'feed') to a
// tenth of its unit a minute; no trailing zeros.
export function fieldText(mm, kind = 'length') {
  const v = toPage(mm);
  return String(Number(v.toFixed(kind === 'feed' ? 1 : 4)));
}

// A size as a machinist reads it: 120.0, 5.00, 0.040 mm; 4.724, 0.250, 0.0394 in.
export function size(mm) {
  if (!inInches()) return Number(mm.toFixed(2)) >= 10 ? mm.toFixed(1) : Number(mm.toPrecision(2)) >= 1 ? mm.toFixed(2) : mm.toPrecision(2);
  const v = mm / INCH;
  return v >= 0.0995 ? v.toFixed(3) : v.toFixed(4);
}
// With its unit: "12.7 mm", "0.500 in".
export const sized = (mm) => `${size(mm)} ${lengthUnit()}`;
// A place or a precise length, to a micron or a tenth: "12.7", "0.5".
export const exact = (mm) => String(Number(toPage(mm).toFixed(inInches() ? 4 : 3)));

// A place or a depth to a hundredth of a mm or a ten-thousandth of an inch: "10.20", "0.4016".
export const place = (mm) => toPage(mm).toFixed(inInches() ? 4 : 2);

// A long distance (a program's cutting length): metres, or inches in thousands.
export const distance = (mm) => (inInches() ? `${Math.round(mm / INCH).toLocaleString()} in` : `${(mm / 1000).toFixed(2)} m`);
// An area and a volume (and a rate of it), rounded.
export const area = (mm2) => (inInches() ? `${(mm2 / INCH ** 2).toLocaleString(undefined, { maximumFractionDigits: 2 })} in²` : `${Math.round(mm2).toLocaleString()} mm²`);
export const volume = (mm3) => (inInches() ? `${(mm3 / INCH ** 3).toLocaleString(undefined, { maximumFractionDigits: 2 })} in³` : `${Math.round(mm3).toLocaleString()} mm³`);
// One length of the page's units in mm (the view's grid steps in powers of ten of it).
export const unitLength = () => (inInches() ? INCH : 1);

// The engine's words in the page's units: its messages say mm ("a step-over of 0.00254 mm",
// "φ6.4 drill in φ6.35 holes: 0.025 mm oversize", "12.0 × 8.0 mm"); in inches each figure
// with its unit (and a φ's) is said in inches, the rest of the sentence as the engine put it.
export const words = (text) => (inInches() && text ? wordsIn(text) : text);

const NUMBER = String.raw`-?(?:\d{1,3}(?:,\d{3})+|\d+)(?:\.\d+)?(?:e[-+]?\d+)?`;
const SPAN = new RegExp(String.raw`((?:${NUMBER}\s*(?:×|x|to|and|–)\s*)*${NUMBER})\s?(mm\/min|mm³|mm²|mm)(?![\w/²³])`, 'g');
const DIAMETER = new RegExp(String.raw`φ(${NUMBER})(?!\s?(?:mm|in)\b|[\d.])`, 'g');
const inchFigure = (v) => (Math.abs(v) >= 1000 ? Math.round(v).toLocaleString('en') : String(Number(v.toPrecision(4))));

// `text` with its millimetre figures in inches (exported for the tests).
export function wordsIn(text) {
  const power = { 'mm/min': 1, mm: 1, 'mm²': 2, 'mm³': 3 };
  const named = { 'mm/min': 'in/min', mm: 'in', 'mm²': 'in²', 'mm³': 'in³' };
  return text
    .replace(SPAN, (_, figures, u) => `${figures.replace(new RegExp(NUMBER, 'g'), (n) => inchFigure(Number(n.replace(/,/g, '')) / INCH ** power[u]))} ${named[u]}`)
    .replace(DIAMETER, (_, n) => `φ${inchFigure(Number(n.replace(/,/g, '')) / INCH)} in`);
}

// What a field holds, by its label: 'length', 'feed', or null (a count, an angle, a ratio).
export function unitOf(el) {
  if (el.dataset.unit !== undefined) return el.dataset.unit || null;
  const text = el.closest('label')?.firstChild?.textContent ?? '';
  const found = /\((mm|in)\/min\b/.test(text) ? 'feed' : /\((mm|in)\b/.test(text) ? 'length' : '';
  el.dataset.unit = found;
  return found || null;
}

// The labels of the length and feed fields (of the settings, or of `root` made anew) say the
// page's units, and their spinners step in them (a step of 1 mm is one of 0.04 in).
export function relabel(root = document.getElementById('settings')) {
  for (const el of root.querySelectorAll('[data-key]')) {
    const label = unitOf(el) && el.closest('label');
    if (!label) continue;
    // The text that names the unit (the label's own, or within its first span), its figures
    // (the depth through a sheet) left standing.
    const walk = document.createTreeWalker(label.firstChild, NodeFilter.SHOW_TEXT);
    for (let t = label.firstChild.nodeType === Node.TEXT_NODE ? label.firstChild : walk.nextNode(); t; t = walk.nextNode()) {
      if (!/\((mm|in)\b/.test(t.textContent)) continue;
      t.textContent = t.textContent.replace(/\((mm|in)(\/min)?\b/, `(${lengthUnit()}$2`);
      break;
    }
    if (el.type !== 'number') continue;
    el.dataset.mmStep ??= el.getAttribute('step') ?? '1';
    const step = el.dataset.mmStep;
    el.setAttribute('step', step === 'any' || !inInches() ? step : String(Number((Number(step) / INCH).toPrecision(1))));
    // Its bounds too (a spinner stops at them).
    for (const bound of ['min', 'max']) {
      const key = `mm${bound}`;
      if (el.dataset[key] === undefined) el.dataset[key] = el.getAttribute(bound) ?? '';
      if (el.dataset[key] !== '') el.setAttribute(bound, String(toPage(Number(el.dataset[key]))));
    }
  }
}

document.body.dataset.units = unit;
relabel();
