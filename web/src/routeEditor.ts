// The route editor: an instructor writes a training route (goals, stages, pass criteria) in YAML, adds stages
// naming the centre's designed exercises or the shipped ones, and the simulator's own route loader checks it
// (errors name the line and field) before it is saved in the centre's route folder. The YAML stays the route.
import { isMap, isSeq, parseDocument, type YAMLMap } from "yaml";

type Api = (path: string, method?: string, body?: unknown) => Promise<{ status: number; data: any }>;
interface CheckedStage {
  id: string; goal: string; exercise: string; exercise_version: string; min_score: number | null;
  bounds: { metric: string; min: number | null; max: number | null }[]; repetitions: number; max_attempts: number;
  requires: string[];
}

const $ = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;
const show = (e: HTMLElement, value: string) => { e.textContent = value; };

export class RouteEditor {
  private timer = 0;
  private request = 0;  // the latest check or save: an earlier check's late answer is dropped
  private machineOf = new Map<string, string>();  // an exercise's machine, as people call it

  constructor(private api: Api, private saved: () => Promise<void>) {
    $("route-load").addEventListener("click", () => this.load());
    $("route-check").addEventListener("click", () => this.act("check"));
    $("route-save").addEventListener("click", () => this.act("save"));
    $("route-add-stage").addEventListener("click", () => this.addStage());
    $("route-text").addEventListener("input", () => this.checkSoon(800));
    $("route-id").addEventListener("change", () => this.checkSoon(0));
  }

  /// The routes to start from and the exercises a stage may name.
  async refresh(routes: { id: string; name: string }[]) {
    const base = $<HTMLSelectElement>("route-base"), kept = base.value;
    base.replaceChildren();
    for (const r of routes) base.add(new Option(`${r.name} (${r.id})`, r.id));
    if (routes.some((r) => r.id === kept)) base.value = kept;
    const exercises: { name: string; title?: string; machine_title?: string }[] =
      (await this.api("/api/exercises")).data ?? [];
    this.machineOf = new Map(exercises.map((e) => [e.name, e.machine_title ?? ""]));
    const select = $<HTMLSelectElement>("route-add-exercise"), chosen = select.value;
    select.replaceChildren();
    for (const e of exercises) select.add(new Option(e.title ? `${e.title} (${e.name})` : e.name, e.name));
    if (exercises.some((e) => e.name === chosen)) select.value = chosen;
  }

  private async load() {
    const id = $<HTMLSelectElement>("route-base").value;
    const r = await this.api(`/api/routes/source?route=${encodeURIComponent(id)}`);
    if (r.status !== 200) { this.verdict(false, r.data?.error ?? `error ${r.status}`); return; }
    // a shipped route is an example: saved under a file name and a title of the centre's own (people pick
    // routes by title, so two alike are refused)
    let text: string = r.data.text;
    if (!r.data.designed) {
      const doc = parseDocument(text);
      if (!doc.errors.length && isMap(doc.contents) && doc.has("name")) {
        doc.set("name", `${String(doc.get("name"))} (centre copy)`);
        text = doc.toString();
      }
    }
    $<HTMLTextAreaElement>("route-text").value = text;
    $<HTMLInputElement>("route-id").value = r.data.designed ? id : `${id}_centre`;
    this.checkSoon(0);
  }

  private checkSoon(ms: number) {
    clearTimeout(this.timer);
    this.timer = window.setTimeout(() => this.act("check"), ms);
    this.verdict(true, "changed: checking…");
  }

  private verdict(ok: boolean, message: string) {
    const result = $("route-result");
    result.className = ok ? "" : "refused";
    show(result, message);
  }

  private async act(action: "check" | "save") {
    clearTimeout(this.timer);
    const request = ++this.request;
    this.verdict(true, action === "check" ? "checking…" : "saving…");
    const r = await this.api(`/api/routes/${action}`, "POST",
      { id: $<HTMLInputElement>("route-id").value, text: $<HTMLTextAreaElement>("route-text").value });
    if (action === "check" && request !== this.request) return;  // a save's answer is always told
    if (r.status !== 200 && r.status !== 201) {
      this.verdict(false, `${action} refused (${r.status}): ${r.data?.error}`);
      return;
    }
    this.stages(r.data.stages as CheckedStage[]);
    if (action === "save") {
      this.verdict(true, `saved ${r.data.id}: ${r.data.stages.length} stages`);
      await this.saved();
      return;
    }
    this.verdict(true, `${r.data.id}: valid, ${r.data.stages.length} stages`);
  }

  // the route as the loader read it: each stage with its exercise's version, criteria and prerequisites
  private stages(stages: CheckedStage[]) {
    const body = $("route-stages").querySelector("tbody")!;
    body.replaceChildren();
    for (const s of stages) {
      const criteria = [s.min_score === null ? "exercise's pass mark" : `score ≥ ${s.min_score}`,
        ...s.bounds.map((b) => [b.min === null ? "" : `${b.metric} ≥ ${b.min}`, b.max === null ? "" : `${b.metric} ≤ ${b.max}`]
          .filter(Boolean).join(", "))].join(", ");
      const row = document.createElement("tr");
      row.dataset.stage = s.id;
      for (const v of [s.goal, s.id, `${s.exercise} (${s.exercise_version.slice(0, 8)})`, criteria,
        `${s.repetitions} of ${s.max_attempts}`, s.requires.join(", ")]) {
        const td = document.createElement("td");
        show(td, v);
        row.append(td);
      }
      body.append(row);
    }
  }

  // a stage naming the chosen exercise, appended to its goal (made when the route has none of that name);
  // the YAML's comments and layout elsewhere are kept
  private addStage() {
    const area = $<HTMLTextAreaElement>("route-text");
    const exercise = $<HTMLSelectElement>("route-add-exercise").value;
    // a new route trains on its first stage's machine
    const machine = JSON.stringify(this.machineOf.get(exercise) || "");
    const doc = parseDocument(area.value.trim() ? area.value : `name: New route\nmachine: ${machine}\ngoals: []\n`);
    if (doc.errors.length) { this.verdict(false, `the YAML does not parse: ${doc.errors[0].message.split("\n")[0]}`); return; }
    const id = $<HTMLInputElement>("route-add-id").value.trim() || exercise;
    const goalName = $<HTMLInputElement>("route-add-goal").value.trim() || "Practice";
    let goals = doc.get("goals");
    if (!isSeq(goals)) { doc.set("goals", doc.createNode([])); goals = doc.get("goals"); }
    const list = goals as { items: unknown[] };
    let goal = list.items.find((g) => isMap(g) && String(g.get("goal")) === goalName) as YAMLMap | undefined;
    if (!goal) {
      goal = doc.createNode({ goal: goalName, stages: [] }) as YAMLMap;
      list.items.push(goal);
    }
    const stage: Record<string, unknown> = { id, exercise };
    const score = $<HTMLInputElement>("route-add-score").value;
    if (score !== "") stage.pass = { score: Number(score) };
    let stages = goal.get("stages");
    if (!isSeq(stages)) { goal.set("stages", doc.createNode([])); stages = goal.get("stages"); }
    (stages as { items: unknown[] }).items.push(doc.createNode(stage, { flow: true }));
    area.value = doc.toString({ lineWidth: 0, flowCollectionPadding: false });
    this.checkSoon(0);
  }
}
