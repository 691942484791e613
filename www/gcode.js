// The program's lines in a pane that draws only those in sight (a program of millions of lines
// scrolls as one of a hundred), with the line of the scrubber's move marked; a click on a line
// calls `onPick(line)`.
const LINE_HEIGHT = 18; // px, as style.css sets `#gcode .line`
const MARGIN = 20; // lines drawn beyond those in sight

export class GcodePane {
  constructor(el, onPick) {
    this.el = el;
    this.onPick = onPick;
    this.bytes = new Uint8Array(0);
    this.decoder = new TextDecoder();
    this.starts = new Uint32Array([0]);
    this.current = -1;
    this.spacer = document.createElement('div');
    this.spacer.className = 'spacer';
    el.replaceChildren(this.spacer);
    el.addEventListener('scroll', () => this.render());
    el.addEventListener('click', (e) => {
      const line = e.target.closest('.line');
      if (line) this.onPick?.(Number(line.dataset.line));
    });
    new ResizeObserver(() => this.render()).observe(el);
  }

  get count() {
    const n = this.bytes.length;
    return this.starts.length - (n && this.bytes[n - 1] === 10 ? 1 : 0);
  }

  // The program as UTF-8 bytes (empty: none) and where each of its lines starts (as the
  // engine gives them, `gcodeBytes` and `lineStarts`): each line is made text only when drawn,
  // so a program of tens of megabytes is never one string here.
  set(bytes, starts) {
    this.bytes = bytes ?? new Uint8Array(0);
    this.starts = starts ?? new Uint32Array([0]);
    this.current = -1;
    this.spacer.style.height = `${this.count * LINE_HEIGHT}px`;
    this.el.scrollTop = 0;
    this.render();
  }

  line(k) {
    const end = k + 1 < this.starts.length ? this.starts[k + 1] - 1 : this.bytes.length;
    return this.decoder.decode(this.bytes.subarray(this.starts[k], end));
  }

  // Marks line `k` (0 first) and scrolls it into sight if it is not.
  setCurrent(k) {
    if (k === this.current) return;
    this.current = k;
    this.reveal();
  }

  // The marked line scrolled into sight (once the pane shows), and the lines drawn.
  reveal() {
    const top = this.current * LINE_HEIGHT, view = this.el.clientHeight;
    if (this.current >= 0 && view > 0 && (top < this.el.scrollTop || top + LINE_HEIGHT > this.el.scrollTop + view)) this.el.scrollTop = Math.max(0, top - view / 3);
    this.render();
  }

  render() {
    if (this.el.hidden || !this.bytes.length) { this.spacer.replaceChildren(); return; }
    const first = Math.max(0, Math.floor(this.el.scrollTop / LINE_HEIGHT) - MARGIN);
    const last = Math.min(this.count, Math.ceil((this.el.scrollTop + this.el.clientHeight) / LINE_HEIGHT) + MARGIN);
    const rows = [];
    for (let k = first; k < last; k++) {
      const row = document.createElement('div');
      row.className = k === this.current ? 'line current' : 'line';
      row.dataset.line = String(k);
      row.style.top = `${k * LINE_HEIGHT}px`;
      const n = document.createElement('span');
      n.className = 'n';
      n.textContent = String(k + 1);
      row.append(n, this.line(k));
      rows.push(row);
    }
    this.spacer.replaceChildren(...rows);
  }
}
