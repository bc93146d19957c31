// The console's live 3D view and 2D plan of one station: the entities the station publishes, drawn with the
// looks the image generator uses (data/visuals/*.yaml, from GET /api/looks), posed by each state at 10 Hz,
// with the ropes' polylines. The 3D view orbits freely (drag: turn, wheel: zoom, right-drag: pan); the plan
// looks straight down on the terminal with the machine's parts named.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

import type { BulkMessage, Jack, Looks, SceneMessage, ViewState } from "./wire";
export type { BulkMessage, HudItem, Looks, SceneMessage, ViewState } from "./wire";

/** The weather as the view shows it: the sky's colour by the time of day (day, dusk, night), greyed by rain
 * cloud, fog and a cover of cloud past 6 oktas as the image generator greys it; the light by day and
 * cloud; fog by the visibility. */
export function weatherLook(hour: number, visibility_m: number, rain_mm_per_h: number, cloud_oktas = 0) {
  // the sun's height over a day at the equinox, as a share of noon's: dusk from 17 h to 19 h, dawn 5 h to 7 h
  const day = Math.min(Math.max(Math.sin(((hour - 6) / 12) * Math.PI) * 4 + 0.5, 0), 1);
  const sky = [0.62, 0.75, 0.88].map((c, i) => c * day + [0.03, 0.04, 0.08][i] * (1 - day));
  const overcast = Math.min(Math.max(rain_mm_per_h / 8, 0), 1);
  const extinction = 3.912 / Math.max(visibility_m, 1) + 0.29e-3 * Math.pow(Math.max(rain_mm_per_h, 0), 0.67);
  const visibility = 3.912 / extinction;
  const cover = Math.min(Math.max(cloud_oktas / 8, 0), 1);
  const grey = Math.max(overcast, Math.min(Math.max((5000 - visibility) / 4500, 0), 1),
    Math.min(Math.max(4 * cover - 3, 0), 1));
  const luminance = (0.30 * sky[0] + 0.59 * sky[1] + 0.11 * sky[2]) * (1 - 0.35 * overcast);
  const colour = sky.map((c, i) => c + (luminance * (i === 2 ? 1.03 : 1) - c) * grey);
  return { colour, visibility_m: visibility, sun: 1.8 * day * (1 - 0.85 * grey), sky: 0.25 + 1.35 * day };
}

const kMostRopePoints = 1024;  // the published state's limit (3072 coordinates)
// drawn in software (no GPU: SwiftShader, llvmpipe), the view is light: a quarter of the pixels and the plan
// once a second (the page draws the station's motion at 5 frames a second then; the orbit stays smooth)
const kLightPixelRatio = 0.5;
const kPlanFrame_ms = 500, kLightPlanFrame_ms = 1000;

/** Whether a WebGL renderer draws without a GPU (the renderer string a browser gives for its software one). */
export function drawsInSoftware(renderer: THREE.WebGLRenderer): boolean {
  const gl = renderer.getContext();
  const info = gl.getExtension("WEBGL_debug_renderer_info");
  const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
  return /swiftshader|llvmpipe|softpipe|software/i.test(name);
}

/** Boxes (or cylinders) drawn as one instanced mesh: a draw call for all of them, whatever their number (a
 * renderer without a GPU pays per draw call). Each box: a unit shape posed and scaled by its matrix, in its own
 * colour. */
class Instances {
  readonly mesh: THREE.InstancedMesh;
  private used = 0;
  constructor(geometry: THREE.BufferGeometry, capacity: number) {
    this.mesh = new THREE.InstancedMesh(geometry, new THREE.MeshLambertMaterial(), Math.max(capacity, 1));
    this.mesh.count = 0;
    this.mesh.frustumCulled = false;  // its bounds change with every pose
  }
  /** A new instance's index. */
  add(matrix: THREE.Matrix4, rgb: number[]): number {
    const n = this.used++;
    this.mesh.setMatrixAt(n, matrix);
    this.mesh.setColorAt(n, new THREE.Color().setRGB(rgb[0], rgb[1], rgb[2], THREE.LinearSRGBColorSpace));
    this.mesh.count = this.used;
    return n;
  }
  set(n: number, matrix: THREE.Matrix4) { this.mesh.setMatrixAt(n, matrix); }
  changed() { this.mesh.instanceMatrix.needsUpdate = true; }
}

/** A part of an entity's look: its instance and where it sits in the entity (a unit box scaled and placed). */
interface PlacedPart { instance: number; local: THREE.Matrix4; }
/** An entity as drawn: its pose from the last state, whether it is there, and its parts. */
interface DrawnEntity { position: THREE.Vector3; quaternion: THREE.Quaternion; visible: boolean; parts: PlacedPart[]; }
/** A jack as drawn: the entities its eyes ride (by index), and its barrel's and rod's instances. */
interface DrawnJack { jack: Jack; from: number; to: number; barrel: number; rod: number; }

const kHidden = new THREE.Matrix4().makeScale(0, 0, 0);

/** A unit box scaled to `size` and centred at `at` (sizes kept above 1 cm: a flat part still has faces). */
// a box of `size` at `at`, its x side turned `along` (a member's length)
function boxMatrix(size: number[], at: number[], along: number[] = [1, 0, 0]): THREE.Matrix4 {
  const turn = new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(1, 0, 0),
    new THREE.Vector3(along[0], along[1], along[2]).normalize());
  return new THREE.Matrix4().compose(new THREE.Vector3(at[0], at[1], at[2]), turn,
    new THREE.Vector3(Math.max(size[0], 0.01), Math.max(size[1], 0.01), Math.max(size[2], 0.01)));
}

export class View3D {
  private readonly renderer: THREE.WebGLRenderer;
  private readonly planRenderer: THREE.WebGLRenderer;
  private readonly scene = new THREE.Scene();
  private readonly camera: THREE.PerspectiveCamera;
  private readonly planCamera = new THREE.OrthographicCamera(-50, 50, 50, -50, 1, 2000);
  private readonly controls: OrbitControls;
  private readonly box = new THREE.BoxGeometry(1, 1, 1);
  private readonly cylinder = new THREE.CylinderGeometry(0.5, 0.5, 1, 16).rotateX(Math.PI / 2);  // upright in z
  private readonly entityGroup = new THREE.Group();  // the entities' instanced boxes
  private readonly ropeGroup = new THREE.Group();
  private readonly bulkGroup = new THREE.Group();
  private bulkQuads = 0;
  private readonly water = new THREE.Mesh(new THREE.PlaneGeometry(3000, 3000),
    new THREE.MeshLambertMaterial({ color: new THREE.Color().setRGB(0.05, 0.16, 0.22, THREE.LinearSRGBColorSpace) }));
  private entities: DrawnEntity[] = [];
  private jacks: DrawnJack[] = [];
  private parts: Instances | null = null;
  private names: string[] = [];
  private attempt = -1;
  private station = "";
  private framed = false;
  private dirty = false;
  private nextPlan = 0;
  private light = false;
  private readonly viewSize: [number, number];  // the canvases' sizes on the page [px]
  private readonly planSize: [number, number];
  private readonly labels: CanvasRenderingContext2D;
  private readonly skyColour = new THREE.Color(0.62, 0.75, 0.88);
  private readonly skyLight = new THREE.HemisphereLight(0xdde8ff, 0x4a4a40, 1.6);
  private readonly sun = new THREE.DirectionalLight(0xffffff, 1.8);
  private weather = "";

  constructor(canvas: HTMLCanvasElement, private readonly planCanvas: HTMLCanvasElement,
    private readonly planLabels: HTMLCanvasElement, private readonly looks: Looks) {
    this.viewSize = [canvas.width, canvas.height];
    this.planSize = [planCanvas.width, planCanvas.height];
    // no multisampling: an instructor's PC may draw it in software (4x the cost)
    this.renderer = new THREE.WebGLRenderer({ canvas, preserveDrawingBuffer: true });
    this.planRenderer = new THREE.WebGLRenderer({ canvas: planCanvas, preserveDrawingBuffer: true });
    this.labels = planLabels.getContext("2d")!;
    this.setLight(drawsInSoftware(this.renderer));
    this.scene.background = this.skyColour;
    this.scene.fog = new THREE.FogExp2(this.skyColour, 0);
    this.scene.add(this.skyLight);
    this.sun.position.set(-60, -40, 120);
    this.scene.add(this.sun);
    this.camera = new THREE.PerspectiveCamera(45, canvas.width / canvas.height, 0.5, 3000);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(-60, -90, 60);
    this.planCamera.up.set(0, 1, 0);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener("change", () => this.invalidate());  // the instructor's orbit: at once
    this.scene.add(this.scenery(), this.water, this.entityGroup, this.ropeGroup, this.bulkGroup);
  }

  /** The station's entities for an attempt (a new attempt replaces them; the same attempt's again, an entity
   *  renamed, redraws them where the view looks). */
  setScene(m: SceneMessage) {
    const again = m.station === this.station && m.attempt === this.attempt;
    this.entityGroup.clear();
    this.parts?.mesh.dispose();
    this.bulkGroup.clear();
    this.bulkQuads = 0;
    // every part of every entity's look: one instanced mesh
    const looks = m.entities.map((e) => this.partsOf(e.visual, e.half_m, e.livery_key));
    // the jacks whose two entities are in this scene (the first with each look), a barrel and a rod each
    const entity = (look: string) => m.entities.findIndex((e) => e.visual === look);
    const jacks = this.looks.jacks.map((jack) => ({ jack, from: entity(jack.from), to: entity(jack.to) }))
      .filter((j) => j.from >= 0 && j.to >= 0);
    this.parts = new Instances(this.box, looks.reduce((sum, l) => sum + l.length, 0) + 2 * jacks.length);
    this.entities = looks.map((l) => ({
      position: new THREE.Vector3(), quaternion: new THREE.Quaternion(), visible: false,
      parts: l.map(({ local, rgb }) => ({ instance: this.parts!.add(kHidden, rgb), local })),
    }));
    this.jacks = jacks.map((j) => ({ ...j, barrel: this.parts!.add(kHidden, j.jack.color),
      rod: this.parts!.add(kHidden, [0.80, 0.80, 0.78]) }));  // the rod chromed
    this.parts.changed();
    this.entityGroup.add(this.parts.mesh);
    this.names = m.entities.map((e) => e.name);
    this.attempt = m.attempt;
    this.station = m.station;
    this.framed = again && this.framed;
    this.invalidate();
  }

  /** The bulk material's surfaces (a sample of another attempt than the scene's is not drawn): a mesh per grid,
   * its quads where there is material. */
  setBulk(m: BulkMessage) {
    if (m.attempt !== this.attempt) return;
    const look = this.looks.visuals["bulk"]?.parts[0]?.color ?? [0.2, 0.2, 0.2];
    while (this.bulkGroup.children.length > m.grids.length) this.bulkGroup.remove(this.bulkGroup.children[m.grids.length]);
    this.bulkQuads = 0;
    m.grids.forEach((g, k) => {
      let mesh = this.bulkGroup.children[k] as THREE.Mesh | undefined;
      if (!mesh) {
        mesh = new THREE.Mesh(new THREE.BufferGeometry(), new THREE.MeshLambertMaterial({
          color: new THREE.Color().setRGB(look[0], look[1], look[2], THREE.LinearSRGBColorSpace), side: THREE.DoubleSide }));
        this.bulkGroup.add(mesh);
      }
      const positions = new Float32Array(3 * g.nx * g.ny);
      for (let j = 0; j < g.ny; ++j)
        for (let i = 0; i < g.nx; ++i) {
          const v = j * g.nx + i;
          positions.set([(i + 0.5) * g.step_m, (j + 0.5) * g.step_m, g.heights[v] ?? 0], 3 * v);
        }
      const index: number[] = [];
      for (let j = 0; j + 1 < g.ny; ++j)
        for (let i = 0; i + 1 < g.nx; ++i) {
          const a = j * g.nx + i, b = a + 1, c = a + g.nx, d = c + 1;
          if (Math.max(g.heights[a], g.heights[b], g.heights[c], g.heights[d]) < 0.02) continue;  // bare floor
          index.push(a, b, d, a, d, c);
          ++this.bulkQuads;
        }
      const geometry = mesh.geometry as THREE.BufferGeometry;
      geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
      geometry.setIndex(index);
      geometry.computeVertexNormals();
      geometry.computeBoundingSphere();
      mesh.position.set(g.pose[0], g.pose[1], g.pose[2]);
      mesh.quaternion.set(g.pose[3], g.pose[4], g.pose[5], g.pose[6]);
    });
    this.invalidate();
  }

  /** Poses and ropes of a state, drawn at once (the page calls it in its frame); a state of another attempt
   * than the scene's is not drawn. */
  /** The sky, the light and the fog for the station's weather (changed only when it changes). */
  setWeather(hour: number, visibility_m: number, rain_mm_per_h: number, cloud_oktas: number) {
    const key = `${hour.toFixed(2)} ${visibility_m.toFixed(0)} ${rain_mm_per_h.toFixed(1)} ${cloud_oktas.toFixed(1)}`;
    if (key === this.weather) return;
    this.weather = key;
    const look = weatherLook(hour, visibility_m, rain_mm_per_h, cloud_oktas);
    this.skyColour.setRGB(look.colour[0], look.colour[1], look.colour[2]);
    const fog = this.scene.fog as THREE.FogExp2;
    fog.color.copy(this.skyColour);
    fog.density = Math.sqrt(3.912) / look.visibility_m;  // exp(-(d x)^2) at 2 % contrast at the visibility
    this.sun.intensity = look.sun;
    this.skyLight.intensity = look.sky;
    this.renderer.domElement.dataset.sky = look.colour.map((c) => c.toFixed(3)).join(" ");
    this.invalidate();
  }

  update(state: ViewState) {
    if (state.attempt !== this.attempt || !state.poses) return;
    this.setWeather(state.time_of_day_h ?? 12, state.visibility_m ?? 20000, state.rain_mm_per_h ?? 0,
      state.cloud_oktas ?? 0);
    const p = state.poses;
    const pose = new THREE.Matrix4(), placed = new THREE.Matrix4(), one = new THREE.Vector3(1, 1, 1);
    this.entities.forEach((e, n) => {
      const q = p.slice(7 * n, 7 * n + 7);
      e.visible = q.length === 7 && (q[3] !== 0 || q[4] !== 0 || q[5] !== 0 || q[6] !== 0);
      if (e.visible) {
        e.position.set(q[0], q[1], q[2]);
        e.quaternion.set(q[3], q[4], q[5], q[6]);
        pose.compose(e.position, e.quaternion, one);
      }
      for (const part of e.parts) this.parts!.set(part.instance, e.visible ? placed.multiplyMatrices(pose, part.local) : kHidden);
    });
    for (const j of this.jacks) this.placeJack(j);
    this.parts?.changed();
    this.drawRopes(state.ropes);
    if (state.water_level_m !== undefined) this.water.position.z = state.water_level_m;
    if (!this.framed) this.frame();
    this.render();
  }

  /** A jack between its eyes as they ride their entities: the barrel from one towards the other, the rod back
   * from the other (as the image generator draws it). */
  private placeJack(j: DrawnJack) {
    const from = this.entities[j.from], to = this.entities[j.to];
    if (!from.visible || !to.visible) {
      this.parts!.set(j.barrel, kHidden);
      this.parts!.set(j.rod, kHidden);
      return;
    }
    const eye = (e: DrawnEntity, at: number[]) => new THREE.Vector3(at[0], at[1], at[2]).applyQuaternion(e.quaternion).add(e.position);
    const a = eye(from, j.jack.from_m), b = eye(to, j.jack.to_m);
    const along = b.clone().sub(a);
    if (along.length() < 1e-6) along.set(1, 0, 0);
    along.normalize();
    const { barrel_m: barrel, rod_m: rod, diameter_m: d } = j.jack;
    const centre = (p: THREE.Vector3, length: number, sign: number) => p.clone().addScaledVector(along, sign * length / 2).toArray();
    this.parts!.set(j.barrel, boxMatrix([barrel, d, d], centre(a, barrel, 1), along.toArray()));
    this.parts!.set(j.rod, boxMatrix([rod, 0.55 * d, 0.55 * d], centre(b, rod, -1), along.toArray()));
  }

  // what the browser tests read: where a jack's barrel and rod are drawn (empty: none in this scene)
  jackEnds(): number[][] {
    const m = new THREE.Matrix4(), at = new THREE.Vector3(), turn = new THREE.Quaternion(), size = new THREE.Vector3();
    return this.jacks.flatMap((j) => [j.barrel, j.rod].map((n) => {
      this.parts!.mesh.getMatrixAt(n, m);
      m.decompose(at, turn, size);
      const half = new THREE.Vector3(size.x / 2, 0, 0).applyQuaternion(turn);
      return [...at.clone().sub(half).toArray(), ...at.clone().add(half).toArray()];
    }));
  }

  /** Light (a quarter of the pixels, the plan once a second) or full; light by default where the browser draws
   * in software. */
  setLight(light: boolean) {
    this.light = light;
    const ratio = light ? kLightPixelRatio : 1;
    for (const [renderer, [width, height]] of [[this.renderer, this.viewSize], [this.planRenderer, this.planSize]] as const) {
      // the drawing buffer scaled, the canvas shown at the page's size
      renderer.setPixelRatio(ratio);
      renderer.setSize(width, height, true);
    }
    this.nextPlan = 0;
    this.invalidate();
  }
  isLight(): boolean { return this.light; }

  // what the browser tests read
  visibleEntities(): number { return this.entities.filter((e) => e.visible).length; }
  bulkQuadsDrawn(): number { return this.bulkQuads; }
  drawnStation(): string { return this.station; }
  cameraPosition(): number[] { return this.camera.position.toArray(); }

  // where an entity's parts lie now (empty: not there)
  private bounds(e: DrawnEntity, into = new THREE.Box3()): THREE.Box3 {
    if (!e.visible) return into;
    const pose = new THREE.Matrix4().compose(e.position, e.quaternion, new THREE.Vector3(1, 1, 1));
    const unit = new THREE.Box3(new THREE.Vector3(-0.5, -0.5, -0.5), new THREE.Vector3(0.5, 0.5, 0.5));
    for (const part of e.parts) into.union(unit.clone().applyMatrix4(new THREE.Matrix4().multiplyMatrices(pose, part.local)));
    return into;
  }

  // A signaller's view: standing on the ground beside the machine, eyes 1.7 m up, looking at where the load
  // hangs (the spreader, hook or grab; else the machine's middle)
  fromTheGround() {
    if (!this.entities.length || !this.entities[0].visible) return;
    const machine = this.bounds(this.entities[0]);
    const load = this.names.findIndex((n) => /^(spreader|hook|grab|load)$/.test(n));
    const target = load >= 0 && this.entities[load].visible
      ? this.bounds(this.entities[load]).getCenter(new THREE.Vector3()) : machine.getCenter(new THREE.Vector3());
    const reach = Math.max(12, 0.6 * machine.getSize(new THREE.Vector3()).length());
    const ground = Math.max(0, machine.min.z);
    this.camera.position.set(target.x - 0.45 * reach, target.y - 0.75 * reach, ground + 1.7);
    this.controls.target.copy(target);
    this.controls.update();
    this.framed = true;
    this.invalidate();
  }

  private frame() {
    // the 3D view: the machine (the scene's first entity) whole, from the landside and above; the plan:
    // everything posed
    if (!this.entities.length || !this.entities[0].visible) return;
    const machine = this.bounds(this.entities[0]);
    const centre = machine.getCenter(new THREE.Vector3());
    const reach = Math.max(30, machine.getSize(new THREE.Vector3()).length());
    this.controls.target.copy(centre);
    this.camera.position.set(centre.x - 0.75 * reach, centre.y - 1.0 * reach, centre.z + 0.45 * reach);
    this.controls.update();
    const bounds = new THREE.Box3();
    for (const e of this.entities) this.bounds(e, bounds);
    const size = bounds.getSize(new THREE.Vector3());
    bounds.getCenter(centre);
    const aspect = this.planCanvas.width / this.planCanvas.height;
    const half = 0.55 * Math.max(size.x / aspect, size.y, 30);
    Object.assign(this.planCamera, { left: -half * aspect, right: half * aspect, top: half, bottom: -half });
    this.planCamera.position.set(centre.x, centre.y, 1000);
    this.planCamera.lookAt(centre.x, centre.y, 0);
    this.planCamera.updateProjectionMatrix();
    this.framed = true;
  }

  // a frame only when something changed: a page that asks for every frame is composited 60 times a second
  private invalidate() {
    if (this.dirty) return;
    this.dirty = true;
    requestAnimationFrame(() => this.render());
  }

  private render() {
    this.dirty = false;
    const now = performance.now();
    this.renderer.render(this.scene, this.camera);
    // the plan at 2 Hz (light: 1 Hz): seen from above, the terminal changes slowly
    if (now < this.nextPlan) return;
    this.nextPlan = now + (this.light ? kLightPlanFrame_ms : kPlanFrame_ms);
    const fog = this.scene.fog;  // the plan is a map: drawn clear whatever the weather
    this.scene.fog = null;
    this.planRenderer.render(this.scene, this.planCamera);
    this.scene.fog = fog;
    // the plan's names: the machine's parts and vehicles, not every container
    const c = this.labels;
    c.clearRect(0, 0, this.planLabels.width, this.planLabels.height);
    c.font = "12px sans-serif";
    c.fillStyle = "#ffffff";
    const taken: number[][] = [];  // label boxes drawn: a name that would overlap one is left out
    this.entities.forEach((e, n) => {
      const name = this.names[n];
      if (!e.visible || /^[A-Z]{4}\d/.test(name) || /^(block|stack|cell|hatch|guide)/i.test(name)) return;
      const at = e.position.clone().project(this.planCamera);
      const x = (at.x + 1) / 2 * this.planLabels.width + 4, y = (1 - at.y) / 2 * this.planLabels.height - 4;
      const box = [x, y - 12, x + c.measureText(name).width, y];
      if (taken.some((t) => box[0] < t[2] && t[0] < box[2] && box[1] < t[3] && t[1] < box[3])) return;
      taken.push(box);
      c.fillText(name, x, y);
    });
  }

  // an entity's look as unit boxes placed in it: boxes, lattice girders as their four chords, members and flights
  // turned along them, any other shape as the box the console sends; an entity without a look is a grey box
  private partsOf(visual: string, half: number[], liveryKey: number): { local: THREE.Matrix4; rgb: number[] }[] {
    const look = this.looks.visuals[visual];
    const own = half.map((h) => 2 * h);
    const placed = (size: number[], at: number[], rgb: number[], along?: number[]) =>
      ({ local: boxMatrix(size, at, along), rgb });
    if (!look) return [placed(own, [0, 0, 0], [0.5, 0.5, 0.5])];
    const parts: { local: THREE.Matrix4; rgb: number[] }[] = [];
    for (const part of look.parts) {
      const size = part.size_m ?? own;
      const rgb = part.livery && look.liveries.length ? look.liveries[liveryKey % look.liveries.length] : part.color;
      if (part.shape === "member" || part.shape === "stairs") { parts.push(placed(size, part.at_m, rgb, part.along)); continue; }
      if (part.shape !== "lattice") { parts.push(placed(size, part.at_m, rgb)); continue; }
      const along = size.indexOf(Math.max(...size));
      for (const a of [-1, 1]) for (const b of [-1, 1]) {
        const chord = size.map((s, k) => (k === along ? s : part.member_m));
        const at = part.at_m.slice();
        const across = [0, 1, 2].filter((k) => k !== along);
        at[across[0]] += a * (size[across[0]] - part.member_m) / 2;
        at[across[1]] += b * (size[across[1]] - part.member_m) / 2;
        parts.push(placed(chord, at, rgb));
      }
    }
    return parts;
  }

  // the quay and the look file's scenery, standing still: an instanced mesh of boxes, one of cylinders
  private scenery(): THREE.Group {
    const group = new THREE.Group();
    const all = this.looks.scenery.flatMap((s) => Array.from({ length: s.repeat }, (_, n) => ({
      shape: s.shape, at: s.at_m.map((v, k) => v + n * s.step_m[k]),
      size: s.shape === "cylinder" ? [s.size_m[0], s.size_m[0], s.size_m[2]] : s.size_m, color: s.color })));
    // the quay as the image generator lays it: its top at z = 0, up to its edge at x = 18 m
    all.push({ shape: "box", at: [-141, 0, -15], size: [318, 800, 30], color: [0.42, 0.42, 0.40] });
    for (const [shape, geometry] of [["box", this.box], ["cylinder", this.cylinder]] as const) {
      const these = all.filter((s) => s.shape === shape);
      if (!these.length) continue;
      const instances = new Instances(geometry, these.length);
      for (const s of these) instances.add(boxMatrix(s.size, s.at), s.color);
      instances.changed();
      group.add(instances.mesh);
    }
    return group;
  }

  private drawRopes(ropes: ViewState["ropes"]) {
    if (!ropes) return;
    while (this.ropeGroup.children.length < ropes.counts.length) {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * kMostRopePoints), 3));
      this.ropeGroup.add(new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0x202020 })));
    }
    let first = 0;
    this.ropeGroup.children.forEach((child, r) => {
      const line = child as THREE.Line;
      const count = r < ropes.counts.length ? Math.min(ropes.counts[r], kMostRopePoints) : 0;
      const position = line.geometry.getAttribute("position") as THREE.BufferAttribute;
      (position.array as Float32Array).set(ropes.points.slice(3 * first, 3 * (first + count)));
      position.needsUpdate = true;
      line.geometry.setDrawRange(0, count);
      line.geometry.computeBoundingSphere();
      line.visible = count > 1;
      first += r < ropes.counts.length ? ropes.counts[r] : 0;
    });
  }
}
