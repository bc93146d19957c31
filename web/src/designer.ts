// The exercise designer's forms: they edit the design's YAML (comments kept) — stowage by clicking a bay's
// slots, trucks, weather and sea state, bulk piles, general cargo, scripted events and faults on a timeline,
// the rubric — and the YAML stays the design: what the simulator's loader checks, previews and saves. The
// forms know nothing of the physics; what a machine offers (its vessel's slots, its event kinds, the rubric
// in force) comes from the console's check of the design.
import { isMap, isSeq, parseDocument, type Document, type YAMLMap, type YAMLSeq } from "yaml";

interface RuleFigure { key: string; value: number; min: number; max: number; }
interface PoseField { key: string; component: number; min: number; max: number; optional: boolean; fallback: number; }
export interface DesignForm {
  machine: string;
  vessel?: { name: string; kind: string; bays: number[]; rows: number[]; hold_tiers: number[]; deck_tiers: number[]; holds: number[] };
  yard_block?: { bays: number; rows: number; tiers: number };
  start_pose: { section: string; fields: PoseField[] };
  sea_harmonic: { max_amplitude_m: number; max_amplitude_deg: number; min_period_s: number; max_period_s: number };
  rules: { thresholds: RuleFigure[]; deductions: RuleFigure[] };
  weather: Record<string, number>;
  event_kinds: string[];
  serves_trucks: boolean;
  catalogue: { vessels: string[]; materials: string[] };
}
type Path = (string | number)[];
type Plain = Record<string, any>;
const X = "exercise";
const BOX_TYPES = ["20ft", "40ft", "40ftHC", "45ftHC"];
// the scripted events' words by their names in the exercise files, from the console's command table
let EVENT_LABEL: Record<string, string> = {};
export function setEventLabels(labels: Record<string, string>) { EVENT_LABEL = labels; }

function el<K extends keyof HTMLElementTagNameMap>(tag: K, props: Partial<HTMLElementTagNameMap[K]> & Plain = {},
  ...children: (Node | string)[]): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(props)) {
    if (k.startsWith("data-")) e.setAttribute(k, String(v));
    else (e as any)[k] = v;
  }
  e.append(...children);
  return e;
}
const svgEl = (tag: string, attrs: Plain) => {
  const e = document.createElementNS("http://www.w3.org/2000/svg", tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  return e;
};
const two = (n: number) => String(n).padStart(2, "0");
// a rule's key in words with its unit: time_limit_s -> "time limit [s]"
const RULE_UNITS: [string, string][] = [["_mps3", "m/s³"], ["_mps", "m/s"], ["_ns", "N·s"], ["_s", "s"], ["_m", "m"]];
function ruleLabel(key: string) {
  const unit = RULE_UNITS.find(([suffix]) => key.endsWith(suffix));
  const words = (unit ? key.slice(0, -unit[0].length) : key).replace(/_/g, " ");
  return unit ? `${words} [${unit[1]}]` : words;
}

export class DesignerForms {
  private doc: Document | null = null;
  private form: DesignForm | null = null;
  private bay = 0;           // the bay (vessel) or block bay shown in the stowage grid
  private selected = "";     // the id of the box whose details are shown
  private pickTargetFor = ""; // a box whose move target the next click on an empty block slot sets
  private event = -1;        // the scripted event whose details are shown
  private pending = false;   // a redraw waiting for the focus to leave the forms

  constructor(private root: HTMLElement, private source: HTMLTextAreaElement, private edited: () => void) {
    root.addEventListener("focusout", () => setTimeout(() => {
      if (this.pending && !root.contains(document.activeElement)) this.render();
    }, 0));
  }

  /// The YAML in the text area changed (loaded or typed): the forms follow it.
  readSource() {
    const doc = parseDocument(this.source.value);
    this.doc = doc.errors.length ? null : doc;
    this.status(doc.errors.length ? `the YAML does not parse: ${doc.errors[0].message.split("\n")[0]}` : "");
    this.render();
  }

  /// A check's verdict on the design: what the forms offer for it.
  setForm(form: DesignForm) {
    this.form = form;
    if (this.root.contains(document.activeElement)) this.pending = true;
    else this.render();
  }

  private status(message: string) {
    const s = document.getElementById("design-form-status");
    if (s) s.textContent = message;
  }

  private js(): Plain { return (this.doc?.toJS() as Plain)?.[X] ?? {}; }
  private get(path: Path): any { return this.doc?.getIn([X, ...path]); }

  // writes a value (or removes the key for undefined) and hands the text back to the text area
  private set(path: Path, value: unknown) {
    if (!this.doc) return;
    if (value === undefined) this.doc.deleteIn([X, ...path]);
    else this.doc.setIn([X, ...path], isMap(value) || isSeq(value) ? value : this.doc.createNode(value, { flow: true }));
    this.commit();
  }
  private commit() {
    if (!this.doc) return;
    this.source.value = this.doc.toString({ lineWidth: 0, flowCollectionPadding: false });
    this.edited();
    this.render();
  }
  private seq(path: Path): YAMLSeq {
    let s = this.get(path);
    if (!isSeq(s)) {
      this.doc!.setIn([X, ...path], this.doc!.createNode([]));
      s = this.get(path);
    }
    return s as YAMLSeq;
  }
  private add(path: Path, item: Plain, at?: number) {
    const seq = this.seq(path);
    const node = this.doc!.createNode(item, { flow: true });
    if (at === undefined) seq.items.push(node);
    else seq.items.splice(at, 0, node);
  }

  // a number field bound to a path: empty removes the key (the default applies, shown as the placeholder)
  private number(label: string, path: Path, opts: { step?: number; min?: number; max?: number; inForce?: number; id?: string } = {}) {
    const value = this.get(path);
    const input = el("input", { type: "number", step: String(opts.step ?? "any"), value: value === undefined ? "" : String(value) });
    if (opts.min !== undefined) input.min = String(opts.min);
    if (opts.max !== undefined) input.max = String(opts.max);
    if (opts.inForce !== undefined) input.placeholder = String(opts.inForce);
    input.dataset.path = path.join(".");
    if (opts.id) input.id = opts.id;
    // checked as typed: a value the field cannot take is said at once and written nowhere
    const why = el("span", { className: "invalid", role: "alert" });
    const valid = () => {
      const bad = input.validity.badInput ? "not a number" : input.validity.rangeUnderflow ? `at least ${input.min}` :
        input.validity.rangeOverflow ? `at most ${input.max}` : "";
      why.textContent = bad ? `${label}: ${bad}` : "";
      input.setAttribute("aria-invalid", String(!!bad));
      return !bad;
    };
    input.addEventListener("input", valid);
    input.addEventListener("change", () => {
      if (valid()) this.set(path, input.value === "" ? undefined : Number(input.value));
    });
    return el("label", {}, label + " ", input, why);
  }

  // a vector's three components in a row (an empty field changes nothing)
  private triple(label: string, path: Path) {
    const inputs = [0, 1, 2].map((k) => {
      const input = el("input", { type: "number", step: "any", value: String(this.get([...path, k]) ?? ""),
        title: `${label.split(" ")[0]} ${"xyz"[k]}` });
      input.dataset.path = [...path, k].join(".");
      input.addEventListener("change", () => { if (input.value !== "") this.set([...path, k], Number(input.value)); });
      return input;
    });
    return el("label", { className: "triple" }, `${label} `, ...inputs);
  }

  render() {
    this.pending = false;
    const parts: HTMLElement[] = [];
    if (this.doc) {
      const x = this.js();
      parts.push(this.basics(x));
      if (this.form?.vessel?.kind === "container") parts.push(this.stowage(x, "slot"));
      if (this.form?.yard_block) parts.push(this.stowage(x, "block_slot"));
      if (x.trucks || this.form?.serves_trucks) parts.push(this.trucks(x));
      parts.push(this.weather(x));
      if (x.bulk) parts.push(this.bulk(x));
      if (x.cargo) parts.push(this.cargo(x));
      parts.push(this.events(x));
      if (this.form) parts.push(this.rubric());
    }
    this.root.replaceChildren(...parts);
  }

  private fieldset(title: string, id: string, ...children: (Node | string)[]) {
    return el("fieldset", { id }, el("legend", {}, title), ...children);
  }

  private basics(x: Plain) {
    const name = el("input", { id: "design-name", value: String(x.name ?? ""), size: 28 });
    name.addEventListener("change", () => this.set(["name"], name.value));
    const row = el("div", { className: "row" }, el("label", {}, "name ", name),
      el("span", {}, `machine: ${this.form?.machine ?? x.machine ?? "?"} (${x.machine ?? ""})`));
    if (x.vessel && this.form) {
      const vessel = el("select", { id: "design-vessel" });
      for (const v of new Set([...this.form.catalogue.vessels, String(x.vessel.file)])) vessel.add(new Option(v, v));
      vessel.value = String(x.vessel.file);
      vessel.addEventListener("change", () => this.set(["vessel", "file"], vessel.value));
      row.append(el("label", {}, "vessel ", vessel));
    }
    return this.fieldset("Exercise", "design-basics", row, this.about(x),
      ...(this.form ? [this.startPose(this.form.start_pose)] : []));
  }

  // what the console's lists say of the exercise: its title (unique among the centre's), objective,
  // difficulty and expected duration
  private about(x: Plain) {
    const about: Plain = x.about ?? {};
    const textField = (key: string, size: number) => {
      const input = el("input", { id: `design-about-${key}`, value: String(about[key] ?? ""), size, spellcheck: true });
      input.addEventListener("change", () => this.set(["about", key], input.value === "" ? undefined : input.value));
      return input;
    };
    const difficulty = el("select", { id: "design-about-difficulty" });
    for (const d of ["", "beginner", "intermediate", "advanced"]) difficulty.add(new Option(d || "(not said)", d));
    difficulty.value = String(about.difficulty ?? "");
    difficulty.addEventListener("change", () => this.set(["about", "difficulty"], difficulty.value || undefined));
    return el("div", { className: "row", id: "design-about" },
      el("label", {}, "title ", textField("title", 36)), el("label", {}, "objective ", textField("objective", 60)),
      el("label", {}, "difficulty ", difficulty),
      this.number("expected min", ["about", "expected_min"], { min: 1, max: 600, id: "design-about-expected_min" }));
  }

  // where the machine stands at the start, in the ranges its machine file allows
  private startPose(pose: DesignForm["start_pose"]) {
    const row = el("div", { className: "row", id: "design-start-pose" }, el("span", {}, "starts at:"));
    for (const f of pose.fields) {
      const label = f.component >= 0 ? `${"xyz"[f.component]} m` : f.key.replace(/_deg$/, " °").replace(/_m$/, " m").replace(/_/g, " ");
      const id = `design-pose-${f.key}${f.component >= 0 ? `-${f.component}` : ""}`;
      if (f.component < 0) {
        row.append(this.number(label, [pose.section, f.key], { min: f.min, max: f.max, id, inForce: f.optional ? f.fallback : undefined }));
        continue;
      }
      // a component of a vector: written in place (an empty field changes nothing)
      const vector = this.get([pose.section, f.key]);
      const input = el("input", { type: "number", step: "any", id, min: String(f.min), max: String(f.max),
        value: isSeq(vector) ? String(vector.get(f.component) ?? "") : "" });
      input.addEventListener("change", () => {
        if (input.value === "" || !isSeq(vector)) return;
        vector.set(f.component, this.doc!.createNode(Number(input.value)));
        this.commit();
      });
      row.append(el("label", {}, label + " ", input));
    }
    return row;
  }

  // The stowage grid of one bay: a vessel's (rows port to starboard, deck tiers over the hatch covers over
  // the hold tiers) or the yard block's (rows across, tiers up from the ground). A click on an empty slot
  // stows a new box there; on a box, shows its details and its goal.
  private stowage(x: Plain, key: "slot" | "block_slot") {
    const onVessel = key === "slot";
    const v = this.form!.vessel, block = this.form!.yard_block;
    const bays = onVessel ? v!.bays : Array.from({ length: block!.bays }, (_, k) => k + 1);
    const boxes: Plain[] = Array.isArray(x.containers) ? x.containers : [];
    const moves: Plain[] = Array.isArray(x.moves) ? x.moves : [];
    if (!bays.includes(this.bay)) {
      const used = boxes.find((b) => Array.isArray(b[key]) && bays.includes(b[key][0]));
      this.bay = used ? used[key][0] : bays[0];
    }
    const baySelect = el("select", { id: onVessel ? "design-bay" : "design-block-bay", ariaLabel: "the bay shown" });
    for (const b of bays) baySelect.add(new Option(`bay ${two(b)}`, String(b)));
    baySelect.value = String(this.bay);
    baySelect.addEventListener("change", () => { this.bay = Number(baySelect.value); this.render(); });
    const newType = el("select", { id: "design-new-type" });
    for (const t of BOX_TYPES) newType.add(new Option(t, t));
    newType.value = sessionStorage.getItem("design-new-type") ?? (onVessel ? "40ft" : "40ftHC");
    newType.addEventListener("change", () => sessionStorage.setItem("design-new-type", newType.value));
    const newMass = el("input", { id: "design-new-mass", type: "number", step: "0.5", min: "1", max: "40",
      value: sessionStorage.getItem("design-new-mass") ?? "22" });
    newMass.addEventListener("change", () => sessionStorage.setItem("design-new-mass", newMass.value));

    const columns = onVessel ? v!.rows : Array.from({ length: block!.rows }, (_, k) => k + 1);
    const tiers: (number | "covers")[] = onVessel ? [...v!.deck_tiers].reverse().concat([]) : [];
    if (onVessel) tiers.push("covers", ...[...v!.hold_tiers].reverse());
    else for (let t = block!.tiers; t >= 1; --t) tiers.push(t);
    const at = (b: Plain) => Array.isArray(b[key]) && b[key][0] === this.bay ? `${b[key][1]},${b[key][2]}` : "";
    const occupant = new Map<string, Plain>(boxes.map((b): [string, Plain] => [at(b), b]).filter(([k]) => k));
    // a box stands on the bottom tier (the hold's floor, the hatch covers, the ground) or on another box:
    // only such slots are offered
    const below = (tier: number) => onVessel ? tier - 2 : tier - 1;
    const bottom = (tier: number) => !onVessel ? tier === 1 :
      tier === (tier >= 80 ? Math.min(...v!.deck_tiers) : Math.min(...v!.hold_tiers));
    const standable = (row: number, tier: number) => bottom(tier) || occupant.has(`${row},${below(tier)}`);
    const targets = new Map<string, string>(moves.filter((m) => Array.isArray(m.block_slot) && m.block_slot[0] === this.bay)
      .map((m): [string, string] => [`${m.block_slot[1]},${m.block_slot[2]}`, String(m.container)]));
    const moved = new Map(moves.map((m) => [String(m.container), m] as const));

    const table = el("table", { className: "stowage", id: onVessel ? "design-stowage" : "design-block" });
    table.append(el("caption", {}, onVessel ? "seen from astern: port ← rows → starboard" : `bay ${two(this.bay)}${this.bay % 2 ? " (20 ft)" : " (40 ft)"}: rows across the block`),
      el("tr", {}, el("th", {}, "tier \\ row"), ...columns.map((r) => el("th", {}, two(r)))));
    for (const tier of tiers) {
      if (tier === "covers") {
        table.append(el("tr", { className: "covers" }, el("td", { colSpan: columns.length + 1 }, "hatch covers")));
        continue;
      }
      const tr = el("tr", {}, el("th", {}, two(tier)));
      for (const row of columns) {
        const slotKey = `${row},${tier}`, box = occupant.get(slotKey), target = targets.get(slotKey);
        const cell = el("td", { "data-slot": `${this.bay},${row},${tier}` });
        if (box) {
          const id = String(box.id);
          cell.className = "box" + (moved.has(id) ? " moved" : "") + (id === this.selected ? " selected" : "");
          cell.title = `${id} ${box.type} ${box.gross_mass_kg ?? ""} kg`;
          cell.append(el("span", {}, id.slice(-4)), el("small", {}, `${box.type}${moved.has(id) ? " →" : ""}`));
        } else if (target) {
          cell.className = "target";
          cell.textContent = `← ${target.slice(-4)}`;
        } else if (!standable(row, tier)) {
          cell.className = "floating";
          cell.title = "nothing below to stand on";
          tr.append(cell);
          continue;
        }
        cell.addEventListener("click", () => this.clickSlot(key, [this.bay, row, tier], box, newType.value, Number(newMass.value)));
        tr.append(cell);
      }
      table.append(tr);
    }
    const hint = this.pickTargetFor ? `click an empty slot: where ${this.pickTargetFor} goes`
      : "click an empty slot to stow a box there, a box to edit it";
    return this.fieldset(onVessel ? `Stowage: ${v!.name}` : "Yard block", onVessel ? "design-stowage-set" : "design-block-set",
      el("div", { className: "row" }, baySelect, el("label", {}, "new box ", newType), el("label", {}, "gross t ", newMass),
        el("span", { className: "hint" }, hint)),
      table, this.boxDetails(x, key));
  }

  private clickSlot(key: string, slot: number[], box: Plain | undefined, type: string, tonnes: number) {
    if (box) {
      this.selected = this.selected === String(box.id) ? "" : String(box.id);
      this.pickTargetFor = "";
      this.render();
      return;
    }
    if (this.pickTargetFor) {
      const id = this.pickTargetFor, m = this.moveIndex(id);
      this.pickTargetFor = "";
      if (m >= 0) {
        this.doc!.deleteIn([X, "moves", m, "to"]);
        this.doc!.setIn([X, "moves", m, "block_slot"], this.doc!.createNode(slot, { flow: true }));
      } else {
        this.add(["moves"], { container: id, block_slot: slot, tolerance_m: 0.1 });
      }
      this.commit();
      return;
    }
    const ids = new Set(((this.js().containers ?? []) as Plain[]).map((b) => String(b.id)));
    let n = 1;
    while (ids.has(`HSIM${String(n).padStart(7, "0")}`)) ++n;
    const id = `HSIM${String(n).padStart(7, "0")}`;
    this.add(["containers"], { id, type, gross_mass_kg: Math.round(tonnes * 1000), [key]: slot });
    this.selected = id;
    this.commit();
  }

  private moveIndex(id: string) {
    const moves: Plain[] = Array.isArray(this.js().moves) ? this.js().moves : [];
    return moves.findIndex((m) => String(m.container) === id);
  }

  // the selected box: id, type, mass, and its goal (stays; to the truck; to a block slot)
  private boxDetails(x: Plain, key: string) {
    const boxes: Plain[] = Array.isArray(x.containers) ? x.containers : [];
    const i = boxes.findIndex((b) => String(b.id) === this.selected && Array.isArray(b[key]));
    if (i < 0) return el("div");
    const box = boxes[i], m = this.moveIndex(this.selected);
    const move = m >= 0 ? x.moves[m] : null;
    const id = el("input", { id: "design-box-id", value: String(box.id), size: 12 });
    id.addEventListener("change", () => {
      this.doc!.setIn([X, "containers", i, "id"], id.value);
      if (m >= 0) this.doc!.setIn([X, "moves", m, "container"], id.value);
      this.selected = id.value;
      this.commit();
    });
    const type = el("select", { id: "design-box-type" });
    for (const t of BOX_TYPES) type.add(new Option(t, t));
    type.value = String(box.type);
    type.addEventListener("change", () => this.set(["containers", i, "type"], type.value));
    const goal = el("select", { id: "design-box-goal" });
    goal.add(new Option("stays", "stays"));
    goal.add(new Option("to the truck", "truck"));
    if (key === "block_slot") goal.add(new Option("to a block slot (click it)", "slot"));
    goal.value = !move ? "stays" : move.to === "truck" ? "truck" : "slot";
    goal.addEventListener("change", () => {
      if (goal.value === "slot") { this.pickTargetFor = this.selected; this.render(); return; }
      if (goal.value === "stays") { if (m >= 0) this.doc!.deleteIn([X, "moves", m]); this.commit(); return; }
      if (m >= 0) {
        this.doc!.deleteIn([X, "moves", m, "block_slot"]);
        this.doc!.setIn([X, "moves", m, "to"], "truck");
      } else {
        this.add(["moves"], { container: this.selected, to: "truck", tolerance_m: 0.3 });
      }
      this.commit();
    });
    const remove = el("button", { id: "design-box-remove", type: "button" }, "remove");
    remove.addEventListener("click", () => {
      if (m >= 0) this.doc!.deleteIn([X, "moves", m]);
      this.doc!.deleteIn([X, "containers", i]);
      this.selected = "";
      this.commit();
    });
    const where = Array.isArray(box[key]) ? `[${box[key].join(", ")}]` : "";
    const row = el("div", { className: "row", id: "design-box" }, el("strong", {}, `box at ${where}`),
      el("label", {}, "id ", id), el("label", {}, "type ", type),
      this.number("gross kg", ["containers", i, "gross_mass_kg"], { min: 1000, max: 40000, step: 100 }),
      el("label", {}, "goal ", goal));
    if (move) row.append(this.number("within m", ["moves", m, "tolerance_m"], { min: 0, max: 5, step: 0.05 }));
    row.append(remove);
    return row;
  }

  private trucks(x: Plain) {
    if (!x.trucks) {
      const add = el("button", { type: "button", id: "design-add-trucks" }, "add a truck lane");
      add.addEventListener("click", () => this.set(["trucks"], { count: 1, lane_x_m: 8.0, stop_y_m: 0.0, chassis_top_m: 1.5 }));
      return this.fieldset("Trucks", "design-trucks", add);
    }
    const delivering = el("input", { type: "checkbox", checked: x.trucks.delivering === true });
    delivering.addEventListener("change", () => this.set(["trucks", "delivering"], delivering.checked ? true : undefined));
    return this.fieldset("Trucks", "design-trucks", el("div", { className: "row" },
      this.number("count", ["trucks", "count"], { min: 1, max: 100, step: 1 }),
      this.number("lane x m", ["trucks", "lane_x_m"], { step: 0.1 }),
      this.number("stop y m", ["trucks", "stop_y_m"], { step: 0.1 }),
      this.number("chassis top m", ["trucks", "chassis_top_m"], { min: 0.5, max: 3, step: 0.05 }),
      el("label", {}, "they bring boxes ", delivering)));
  }

  private weather(x: Plain) {
    const w = ["weather"], inForce = (key: string) => this.form?.weather?.[key];
    const field = (label: string, key: string, opts: { min?: number; max?: number; step?: number; id?: string }) =>
      this.number(label, [...w, key], { ...opts, inForce: inForce(key) });
    const row = el("div", { className: "row" },
      field("wind m/s", "wind_mean_mps", { min: 0, step: 0.5, id: "design-wind" }),
      field("from °", "wind_from_deg", { min: 0, max: 360, step: 5 }),
      field("turbulence", "turbulence_intensity", { min: 0, max: 1, step: 0.01 }),
      field("visibility m", "visibility_m", { min: 1, step: 100 }),
      field("rain mm/h", "rain_mm_per_h", { min: 0, max: 500, step: 0.5 }),
      field("cloud oktas", "cloud_oktas", { min: 0, max: 8, step: 1 }),
      field("time of day h", "time_of_day_h", { min: 0, max: 24, step: 0.25 }));
    const parts: HTMLElement[] = [row];
    // the vessel's motion: a sum of harmonics per motion (the first one offered empty when there is none)
    if (x.vessel) {
      parts.push(el("div", { className: "hint" }, "sea state: the vessel's heave, roll and pitch, each a sum of harmonics"));
      const range = this.form?.sea_harmonic;
      for (const [motion, unit] of [["heave", "m"], ["roll", "deg"], ["pitch", "deg"]] as const) {
        const list: Plain[] = Array.isArray(x.vessel.sea_state?.[motion]) ? x.vessel.sea_state[motion] : [];
        const row = el("div", { className: "row", id: `design-sea-${motion}` }, el("span", {}, `${motion}:`));
        for (let k = 0; k < Math.max(list.length, 1); ++k) {
          const path = ["vessel", "sea_state", motion, k];
          const harmonic = el("span", { className: "harmonic" },
            this.number(unit === "m" ? "amplitude m" : "amplitude °", [...path, `amplitude_${unit}`], { min: 0, max: range?.[`max_amplitude_${unit}`], step: 0.01 }),
            this.number("period s", [...path, "period_s"], { min: range?.min_period_s, max: range?.max_period_s, step: 0.5 }),
            this.number("phase °", [...path, "phase_deg"], { min: -360, max: 360, step: 5, inForce: 0 }));
          if (k < list.length) {
            const remove = el("button", { type: "button", title: `remove this ${motion} harmonic` }, "×");
            remove.addEventListener("click", () => {
              this.doc!.deleteIn([X, ...path]);
              if (list.length === 1) this.doc!.deleteIn([X, "vessel", "sea_state", motion]);
              this.commit();
            });
            harmonic.append(remove);
          }
          row.append(harmonic);
        }
        if (list.length) {
          const add = el("button", { type: "button", id: `design-sea-${motion}-add` }, `+ ${motion} harmonic`);
          const last = list[list.length - 1];
          add.addEventListener("click", () => {
            this.add(["vessel", "sea_state", motion], { [`amplitude_${unit}`]: last[`amplitude_${unit}`] ?? 0, period_s: last.period_s ?? 10 });
            this.commit();
          });
          row.append(add);
        }
        parts.push(row);
      }
    }
    return this.fieldset("Weather and sea", "design-weather", ...parts);
  }

  private bulk(x: Plain) {
    const b = x.bulk as Plain;
    const material = el("select", { id: "design-material" });
    for (const m of new Set([...(this.form?.catalogue.materials ?? []), String(b.material)])) material.add(new Option(m, m));
    material.value = String(b.material);
    material.addEventListener("change", () => this.set(["bulk", "material"], material.value));
    const parts: HTMLElement[] = [el("div", { className: "row" }, el("label", {}, "material ", material))];
    (Array.isArray(b.grids) ? b.grids : []).forEach((g: Plain, k: number) =>
      parts.push(el("div", { className: "row" }, el("span", {}, `grid ${g.name}${g.vessel_hold ? ` (hold ${g.vessel_hold})` : ""}:`),
        this.number("filled to m", ["bulk", "grids", k, "fill_m"], { min: 0, max: 50, step: 0.1 }))));
    const heaps: Plain[] = Array.isArray(b.heaps) ? b.heaps : [];
    heaps.forEach((h, k) => {
      const remove = el("button", { type: "button" }, "remove");
      remove.addEventListener("click", () => this.set(["bulk", "heaps", k], undefined));
      parts.push(el("div", { className: "row" }, el("span", {}, `heap on ${h.grid}:`),
        this.number("x m", ["bulk", "heaps", k, "x_m"], { min: 0, step: 0.5 }),
        this.number("y m", ["bulk", "heaps", k, "y_m"], { min: 0, step: 0.5 }),
        this.number("m³", ["bulk", "heaps", k, "volume_m3"], { min: 0, step: 10 }), remove));
    });
    const quayGrids = (Array.isArray(b.grids) ? b.grids : []).filter((g: Plain) => !g.vessel_hold);
    if (quayGrids.length) {
      const add = el("button", { type: "button", id: "design-add-heap" }, `add a heap on ${quayGrids[0].name}`);
      add.addEventListener("click", () => {
        const g = quayGrids[0];
        this.add(["bulk", "heaps"], { grid: g.name, x_m: (g.cells_x * g.cell_size_m) / 2, y_m: (g.cells_y * g.cell_size_m) / 2, volume_m3: 100 });
        this.commit();
      });
      parts.push(el("div", { className: "row" }, add));
    }
    const goal = el("div", { className: "row" });
    if (x.deliver) goal.append(this.number(`tonnes into ${x.deliver.into}`, ["deliver", "tonnes"], { min: 0, step: 1 }));
    if (x.trim) goal.append(this.number(`trim ${x.trim.grid} down to m`, ["trim", "top_m"], { step: 0.1 }));
    parts.push(goal);
    return this.fieldset("Bulk", "design-bulk", ...parts);
  }

  // General cargo on the MHC's hook: each piece (its size, mass, where it stands) and where it is to go.
  private cargo(x: Plain) {
    const pieces: Plain[] = Array.isArray(x.cargo) ? x.cargo : [];
    const moves: Plain[] = Array.isArray(x.moves) ? x.moves : [];
    const parts: HTMLElement[] = pieces.map((piece, i) => {
      const id = el("input", { value: String(piece.id ?? ""), size: 10, id: `design-cargo-id-${i}` });
      const m = moves.findIndex((move) => String(move.cargo) === String(piece.id));
      id.addEventListener("change", () => {
        this.doc!.setIn([X, "cargo", i, "id"], id.value);
        if (m >= 0) this.doc!.setIn([X, "moves", m, "cargo"], id.value);
        this.commit();
      });
      const remove = el("button", { type: "button" }, "remove");
      remove.addEventListener("click", () => {
        if (m >= 0) this.doc!.deleteIn([X, "moves", m]);
        this.doc!.deleteIn([X, "cargo", i]);
        this.commit();
      });
      const piece_ = el("div", { className: "piece", "data-cargo": String(i) },
        el("div", { className: "row" }, el("label", {}, "id ", id),
          this.number("kg", ["cargo", i, "mass_kg"], { min: 1, step: 100, id: `design-cargo-mass-${i}` }),
          this.number("yaw °", ["cargo", i, "yaw_deg"], { step: 1 }), remove),
        el("div", { className: "row" }, this.triple("size x y z m", ["cargo", i, "size_m"]),
          this.triple("stands at x y z m", ["cargo", i, "position_m"])));
      if (m >= 0) piece_.append(el("div", { className: "row" }, this.triple("goes to x y z m", ["moves", m, "target_m"]),
        this.number("within m", ["moves", m, "tolerance_m"], { min: 0, max: 5, step: 0.05 })));
      return piece_;
    });
    // a new piece beside the last one, going beside the last one's target (the check says where that is wrong)
    const add = el("button", { type: "button", id: "design-add-cargo" }, "add a piece");
    add.addEventListener("click", () => {
      const last = pieces[pieces.length - 1] ?? { size_m: [3, 2, 2], position_m: [0, 0, 1] };
      const lastMove = moves.find((move) => String(move.cargo) === String(last.id));
      const size: number[] = Array.isArray(last.size_m) ? last.size_m : [3, 2, 2];
      const step = Math.max(...size) + 2;
      const beside = (at: unknown) => Array.isArray(at) ? [Number(at[0]), Number(at[1]) + step, Number(at[2])] : [0, step, size[2] / 2];
      let n = pieces.length + 1;
      while (pieces.some((piece) => String(piece.id) === `PIECE-${n}`)) n++;
      this.add(["cargo"], { id: `PIECE-${n}`, size_m: size, mass_kg: 10000, position_m: beside(last.position_m), yaw_deg: 0 });
      this.add(["moves"], { cargo: `PIECE-${n}`, target_m: beside(lastMove?.target_m ?? last.position_m), tolerance_m: 0.5 });
      this.commit();
    });
    parts.push(el("div", { className: "row" }, add));
    return this.fieldset("General cargo", "design-cargo", ...parts);
  }

  // Scripted events and faults on a timeline over the time limit: a click on the line adds the chosen kind
  // at that second; a click on a marker shows its details.
  private events(x: Plain) {
    const events: Plain[] = Array.isArray(x.events) ? x.events : [];
    // an event comes at an exercise time or so long after the first lift (drawn below the line, hollow)
    const fromLift = (e: Plain) => e.after_lift_s !== undefined;
    // a figure the text holds that is not a number yet (the instructor is typing): drawn at the default, so the
    // timeline never draws at NaN; the check names the field
    const finite = (value: unknown, fallback: number) => Number.isFinite(Number(value)) ? Number(value) : fallback;
    const when = (e: Plain) => finite(fromLift(e) ? e.after_lift_s : e.at_s, 0);
    const fallbackLimit = finite(this.form?.rules.thresholds.find((f) => f.key === "time_limit_s")?.value, 600);
    const limit = finite(x.rules?.time_limit_s ?? fallbackLimit, fallbackLimit);
    const span = Math.max(limit, ...events.map((e) => when(e) + 10));
    const W = 640, H = 64, left = 10, right = W - 10, y = 36;
    const tx = (t: number) => left + ((right - left) * t) / span;
    const kinds = this.form?.event_kinds ?? [];
    const kind = el("select", { id: "design-event-kind" });
    for (const k of kinds) kind.add(new Option(EVENT_LABEL[k] ?? k, k));
    const remembered = sessionStorage.getItem("design-event-kind");
    kind.value = remembered && kinds.includes(remembered) ? remembered : "gust";  // another machine's fault: not here
    kind.addEventListener("change", () => sessionStorage.setItem("design-event-kind", kind.value));
    const svg = svgEl("svg", { id: "design-timeline", width: W, height: H, viewBox: `0 0 ${W} ${H}`, "data-span": span });
    svg.append(svgEl("rect", { x: 0, y: 0, width: W, height: H, fill: "#f7f9fc" }),
      svgEl("line", { x1: left, x2: right, y1: y, y2: y, stroke: "#556", "stroke-width": 2 }));
    const step = span > 1200 ? 300 : span > 400 ? 60 : 30;
    for (let t = 0; t <= span; t += step) {
      svg.append(svgEl("line", { x1: tx(t), x2: tx(t), y1: y - 4, y2: y + 4, stroke: "#556" }));
      const label = svgEl("text", { x: tx(t), y: H - 6, "font-size": 10, "text-anchor": "middle", fill: "#556" });
      label.textContent = `${t} s`;
      svg.append(label);
    }
    svg.append(svgEl("line", { x1: tx(limit), x2: tx(limit), y1: 8, y2: y + 6, stroke: "#b00020", "stroke-dasharray": "3 2" }));
    svg.addEventListener("click", (e) => {
      const box = svg.getBoundingClientRect();
      const t = Math.round(((e.clientX - box.left) * (W / box.width) - left) / (right - left) * span);
      if (t < 0 || t > span) return;
      const item: Plain = { at_s: t, kind: kind.value };
      if (kind.value === "gust") Object.assign(item, { amplitude_mps: 6, duration_s: 3 });
      if (kind.value === "landed_sensor_fault") item.corner = 0;
      const at = events.filter((ev) => when(ev) <= t).length;  // the loader wants them in time order
      this.add(["events"], item, at);
      this.event = at;
      this.commit();
    });
    events.forEach((ev, k) => {
      const fault = ev.kind !== "gust";
      const colour = fault ? "#d62828" : "#1d70b8";
      const marker = svgEl("circle", { cx: tx(when(ev)), cy: fromLift(ev) ? y + 12 : y, r: k === this.event ? 8 : 6,
        fill: fromLift(ev) ? "#fff" : colour, stroke: fromLift(ev) ? colour : "#123", "stroke-width": fromLift(ev) ? 3 : 1,
        "data-event": k, class: "event-marker" });
      const title = svgEl("title", {});
      title.textContent = `${when(ev)} s${fromLift(ev) ? " after the first lift" : ""}: ${EVENT_LABEL[ev.kind] ?? ev.kind}`;
      marker.append(title);
      marker.addEventListener("click", (e) => { e.stopPropagation(); this.event = k; this.render(); });
      const label = svgEl("text", { x: tx(when(ev)), y: 16, "font-size": 10, "text-anchor": "middle", fill: "#123" });
      label.textContent = fault ? (EVENT_LABEL[ev.kind] ?? ev.kind).replace(" fault", "") : `+${ev.amplitude_mps ?? "?"} m/s`;
      svg.append(marker, label);
    });
    const parts: (Node | string)[] = [el("div", { className: "row" }, el("label", {}, "click the line to add ", kind),
      el("span", { className: "hint" }, `${events.length} scripted; the dashed line is the time limit; hollow: timed from the first lift`)), svg];
    if (this.event >= events.length) this.event = -1;
    if (this.event >= 0) {
      const k = this.event, ev = events[k];
      const path = ["events", k];
      const at = el("input", { id: "design-event-at", type: "number", min: "0", step: "1", value: String(when(ev)) });
      const lifted = el("input", { id: "design-event-from-lift", type: "checkbox" });
      lifted.checked = fromLift(ev);
      const move = () => {
        // moved in time (or to the other clock): the list is kept in time order, which keeps each clock's too
        const seq = this.seq(["events"]);
        const [node] = seq.items.splice(k, 1) as YAMLMap[];
        const key = lifted.checked ? "after_lift_s" : "at_s", fresh = !node.has(key);
        node.delete(lifted.checked ? "at_s" : "after_lift_s");
        node.set(key, Number(at.value));
        if (fresh) node.items.unshift(node.items.pop()!);  // the time first, as written by hand
        const rest: Plain[] = (seq.toJSON() as Plain[]);
        const to = rest.filter((e) => when(e) <= Number(at.value)).length;
        seq.items.splice(to, 0, node);
        this.event = to;
        this.commit();
      };
      at.addEventListener("change", move);
      lifted.addEventListener("change", move);
      const remove = el("button", { type: "button", id: "design-event-remove" }, "remove");
      remove.addEventListener("click", () => { this.event = -1; this.set(path, undefined); });
      const row = el("div", { className: "row", id: "design-event" }, el("strong", {}, EVENT_LABEL[ev.kind] ?? ev.kind),
        el("label", {}, "at s ", at), el("label", {}, lifted, " after the first lift"));
      if (ev.kind === "gust") row.append(this.number("+ m/s", [...path, "amplitude_mps"], { min: 0, step: 0.5 }),
        this.number("for s", [...path, "duration_s"], { min: 0, step: 0.5 }));
      if (ev.kind === "landed_sensor_fault") row.append(this.number("corner", [...path, "corner"], { min: 0, max: 3, step: 1 }));
      row.append(remove);
      parts.push(row);
    }
    return this.fieldset("Events and faults", "design-events", ...parts);
  }

  // The rubric: pass mark, time limit and thresholds, points per occurrence; the figure in force (a default
  // when the design sets none) is the field's placeholder.
  private rubric() {
    const f = this.form!;
    const grid = (title: string, figures: RuleFigure[], base: Path) => el("div", { className: "rubric" },
      el("strong", {}, title), ...figures.map((r) => this.number(ruleLabel(r.key), [...base, r.key],
        { min: r.min, max: r.max, inForce: r.value, id: `design-rule-${r.key}` })));
    return this.fieldset("Rubric", "design-rubric",
      grid("thresholds", f.rules.thresholds, ["rules"]),
      grid("points deducted per occurrence", f.rules.deductions, ["rules", "deductions"]));
  }
}
