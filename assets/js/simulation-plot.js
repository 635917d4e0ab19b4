// The live plots of the Simulate mode (assets/js/simulation.js), on a 2D canvas.
// TracePlot: the lesson's traced values against simulated time, over the last WINDOW
// seconds: for a position lesson, each joint's set point (a step line, as the Python
// lesson's figure draws it) and its position; for a pulse lesson, each wheel's speed.
// PathPlot: the car's path seen from above, with the circle of Eq. 4's radius.

const WINDOW = 10; // s shown
const COLORS = ["#d62728", "#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b"];
const MARGIN = { left: 52, right: 20, top: 8, bottom: 26 };   // right: room for the last time label


// The canvas sized to its box at the screen's pixel ratio, cleared, with a context that
// draws in CSS pixels: { g, width, height }.
function cleared(canvas) {
  const width = canvas.clientWidth || 600;
  const height = canvas.clientHeight || 200;
  const ratio = window.devicePixelRatio || 1;
  if (canvas.width !== Math.round(width * ratio)) canvas.width = Math.round(width * ratio);
  if (canvas.height !== Math.round(height * ratio)) canvas.height = Math.round(height * ratio);
  const g = canvas.getContext("2d");
  g.setTransform(ratio, 0, 0, ratio, 0, 0);
  g.clearRect(0, 0, width, height);
  return { g, width, height };
}

export class TracePlot {
  // series: [{label, column, step}], `column` in the worker's trace rows (0 is time).
  constructor(canvas, series, unit) {
    Object.assign(this, { canvas, series, unit, rows: [] });
  }

  clear() {
    this.rows = [];
    this.draw();
  }

  add(rows) {
    this.rows.push(...rows);
    const last = this.rows.length ? this.rows[this.rows.length - 1][0] : 0;
    const first = this.rows.findIndex((row) => row[0] >= last - WINDOW);
    if (first > 0) this.rows.splice(0, first);
  }

  draw() {
    const { canvas, rows } = this;
    const { g, width, height } = cleared(canvas);
    const t1 = Math.max(WINDOW, rows.length ? rows[rows.length - 1][0] : 0);
    const t0 = t1 - WINDOW;
    let low = Infinity;
    let high = -Infinity;
    for (const row of rows) {
      for (const s of this.series) {
        low = Math.min(low, row[s.column]);
        high = Math.max(high, row[s.column]);
      }
    }
    if (!(high > low)) { low = (Number.isFinite(low) ? low : 0) - 1; high = low + 2; }
    const pad = 0.08 * (high - low);
    low -= pad;
    high += pad;
    const plotW = width - MARGIN.left - MARGIN.right;
    const plotH = height - MARGIN.top - MARGIN.bottom;
    const x = (t) => MARGIN.left + ((t - t0) / WINDOW) * plotW;
    const y = (v) => MARGIN.top + (1 - (v - low) / (high - low)) * plotH;

    g.strokeStyle = "#9a9a9a";
    g.lineWidth = 1;
    g.strokeRect(MARGIN.left, MARGIN.top, plotW, plotH);
    g.fillStyle = "#444";
    g.font = "12px system-ui, sans-serif";
    g.textAlign = "right";
    g.textBaseline = "middle";
    for (const v of [low + pad, (low + high) / 2, high - pad]) {
      g.fillText(v.toFixed(Math.abs(high - low) < 1 ? 3 : 2).replace("-", "\u2212"),
        MARGIN.left - 4, y(v));
    }
    g.textAlign = "center";
    g.textBaseline = "top";
    for (let t = Math.ceil(t0); t <= t1; t += 2) g.fillText(`${t} s`, x(t), height - 20);

    this.series.forEach((s, index) => {
      g.strokeStyle = COLORS[index % COLORS.length];
      g.lineWidth = 1.5;
      g.beginPath();
      rows.forEach((row, i) => {
        const px = x(row[0]);
        const py = y(row[s.column]);
        if (i === 0) g.moveTo(px, py);
        else if (s.step) { g.lineTo(px, y(rows[i - 1][s.column])); g.lineTo(px, py); }
        else g.lineTo(px, py);
      });
      g.stroke();
    });
  }
}

// The plot's legend as HTML, so that a screen reader can read it.
export function legend(list, series) {
  list.replaceChildren(...series.map((s, index) => {
    const item = document.createElement("li");
    const swatch = document.createElement("span");
    swatch.className = "simulation-swatch";
    swatch.style.background = COLORS[index % COLORS.length];
    item.append(swatch, s.label);
    return item;
  }));
}

// The path of the rear axle's centre from above, x to the right and y up, at one scale,
// and a dashed circle (`circle`: {x, y, radius}) where Eq. 4 says the path should run.
export class PathPlot {
  constructor(canvas) {
    Object.assign(this, { canvas, rows: [], circle: null });
  }

  clear() {
    this.rows = [];
    this.circle = null;
    this.draw();
  }

  add(rows) {
    this.rows.push(...rows);
    const last = this.rows.length ? this.rows[this.rows.length - 1][0] : 0;
    const first = this.rows.findIndex((row) => row[0] >= last - 6 * WINDOW);
    if (first > 0) this.rows.splice(0, first);
  }

  draw() {
    const { canvas, rows, circle } = this;
    const { g, width, height } = cleared(canvas);
    const xs = rows.map((row) => row[1]);
    const ys = rows.map((row) => row[2]);
    if (circle && Number.isFinite(circle.radius)) {
      xs.push(circle.x - circle.radius, circle.x + circle.radius);
      ys.push(circle.y - circle.radius, circle.y + circle.radius);
    }
    if (!xs.length) { xs.push(-1, 1); ys.push(-1, 1); }
    const [x0, x1] = [Math.min(...xs), Math.max(...xs)];
    const [y0, y1] = [Math.min(...ys), Math.max(...ys)];
    const span = Math.max(x1 - x0, y1 - y0, 0.5) * 1.15;
    const scale = Math.min(width - 20, height - 20) / span;
    const cx = (x0 + x1) / 2;
    const cy = (y0 + y1) / 2;
    const px = (x) => width / 2 + (x - cx) * scale;
    const py = (y) => height / 2 - (y - cy) * scale;
    g.fillStyle = "#444";
    g.font = "12px system-ui, sans-serif";
    g.fillText(`1 m = ${Math.round(scale)} px`, 8, 16);
    if (circle && Number.isFinite(circle.radius)) {
      g.strokeStyle = COLORS[0];
      g.setLineDash([6, 4]);
      g.beginPath();
      g.arc(px(circle.x), py(circle.y), circle.radius * scale, 0, 2 * Math.PI);
      g.stroke();
      g.setLineDash([]);
    }
    g.strokeStyle = COLORS[1];
    g.lineWidth = 1.5;
    g.beginPath();
    rows.forEach((row, i) => (i ? g.lineTo : g.moveTo).call(g, px(row[1]), py(row[2])));
    g.stroke();
  }
}
