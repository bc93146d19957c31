// The station's live telemetry as three plots, a minute each: the load and what the ropes carry, the load's
// swing and the wind, the motions' speeds. Which figures go where is read from their names (the simulator
// publishes them machine-blind: load_t, rope_tension_kn, swing_m, <axis>_speed_mps); a figure a machine lacks
// is left out, and a plot with nothing of the machine's to show is hidden.
import uPlot from "uplot";

interface SeriesRule { match: RegExp; label: (name: string) => string; scale: string; }
interface PlotRule { id: string; title: string; series: SeriesRule[]; }

const kWind = "wind";  // not an indicator: the wind speed at the station, from the state's wind vector
const kPlots: PlotRule[] = [
  { id: "load", title: "load and ropes", series: [
    { match: /^load_t$/, label: () => "load [t]", scale: "t" },
    { match: /^rope_tension_kn$/, label: () => "rope tension, most loaded fall [kN]", scale: "kN" }] },
  { id: "sway", title: "swing and wind", series: [
    { match: /^swing_m$/, label: () => "swing from plumb [m]", scale: "m" },
    { match: /^wind$/, label: () => "wind [m/s]", scale: "m/s" }] },
  { id: "speeds", title: "speeds", series: [
    { match: /_speed_mps$/, label: (n) => `${n.replace(/_speed_mps$/, "").replace(/_/g, " ")} [m/s]`, scale: "m/s" }] },
];
const kColours = ["#e63946", "#2a9d8f", "#f4a261", "#6a4c93", "#457b9d", "#264653"];
const kSamples = 600;  // a minute at the states' 10 a second

interface Plotted { rule: PlotRule; names: string[]; data: number[][]; plot: uPlot | null; box: HTMLElement; }

export class TelemetryPlots {
  private plots: Plotted[] = [];
  private time: number[] = [];
  private shape = "";

  constructor(private readonly parent: HTMLElement) {}

  /// Forgets what was plotted (another station chosen).
  clear() {
    for (const p of this.plots) p.plot?.destroy();
    this.plots = [];
    this.time = [];
    this.shape = "";
    this.parent.replaceChildren();
  }

  /// Keeps one state's figures; a time going back or jumping (a replay's seek) starts the minute anew.
  keep(time_s: number, wind_mps: number, indicators: Record<string, number>) {
    const names = [...Object.keys(indicators), kWind];
    if (names.join() !== this.shape) this.build(names);
    const last = this.time.length ? this.time[this.time.length - 1] : time_s;
    if (time_s < last || time_s - last > 1) this.restart();
    this.time.push(time_s);
    for (const p of this.plots)
      p.names.forEach((n, k) => p.data[k].push(n === kWind ? wind_mps : indicators[n]));
    if (this.time.length > kSamples) {
      this.time.shift();
      for (const p of this.plots) for (const column of p.data) column.shift();
    }
  }

  /// Draws what was kept.
  draw(title: string) {
    for (const p of this.plots) {
      if (!p.plot) p.plot = this.create(p, title);
      p.plot.setData([this.time, ...p.data] as uPlot.AlignedData);
    }
  }

  private restart() {
    this.time.length = 0;
    for (const p of this.plots) for (const column of p.data) column.length = 0;
  }

  private build(names: string[]) {
    this.clear();
    this.shape = names.join();
    for (const rule of kPlots) {
      const chosen = rule.series.flatMap((s) => names.filter((n) => s.match.test(n)));
      if (chosen.every((n) => n === kWind)) continue;  // nothing of the machine's (the wind has its own line)
      const box = document.createElement("div");
      box.className = "telemetry-plot";
      box.dataset.plot = rule.id;
      box.dataset.series = chosen.join(",");
      this.parent.appendChild(box);
      this.plots.push({ rule, names: chosen, data: chosen.map(() => []), plot: null, box });
    }
  }

  // one or two value scales: the first on the left axis, a second (another unit) on the right
  private create(p: Plotted, station: string): uPlot {
    const ruleOf = (n: string) => p.rule.series.find((s) => s.match.test(n))!;
    const scales = [...new Set(p.names.map((n) => ruleOf(n).scale))];
    const axes: uPlot.Axis[] = [{}, { scale: scales[0], label: scales[0] }];
    if (scales.length > 1) axes.push({ scale: scales[1], label: scales[1], side: 1, grid: { show: false } });
    const width = Math.min(1100, window.innerWidth - 80);
    return new uPlot({
      width: this.plots.length > 1 ? Math.max(320, Math.floor(width / Math.min(this.plots.length, 3)) - 12) : width,
      height: 220, title: `${station}: ${p.rule.title}`,
      series: [{ label: "time [s]" }, ...p.names.map((n, k) => ({
        label: ruleOf(n).label(n), scale: ruleOf(n).scale, stroke: kColours[k % kColours.length], width: 1.5 }))],
      axes, scales: { x: { time: false } },
    }, [this.time, ...p.data] as uPlot.AlignedData, p.box);
  }
}
