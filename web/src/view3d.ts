// The console's live 3D view and 2D plan of one station: the entities the station publishes, drawn with the
// looks the image generator uses (data/visuals/*.yaml, from GET /api/looks), posed by each state at 10 Hz,
// with the ropes' polylines. The 3D view orbits freely (drag: turn, wheel: zoom, right-drag: pan); the plan
// looks straight down on the terminal with the machine's parts named.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

interface Part {
  shape: "box" | "lattice" | "mesh"; size_m: number[] | null; at_m: number[]; color: number[];
  livery: boolean; bay_m: number; member_m: number;
}
interface Scenery { shape: "box" | "cylinder"; at_m: number[]; size_m: number[]; color: number[]; repeat: number; step_m: number[]; }
export interface Looks { visuals: Record<string, { parts: Part[]; liveries: number[][] }>; scenery: Scenery[]; }
export interface SceneMessage {
  station: string; attempt: number; machine: string;
  entities: { name: string; visual: string; half_m: number[] }[];
}
/** A station's bulk material: each grid's samples (nx by ny, step_m apart), its pose (corner, quaternion) and
 * the heights above its floor, row by row. */
export interface BulkMessage {
  attempt: number; grids: { nx: number; ny: number; step_m: number; pose: number[]; heights: number[] }[];
}
export interface ViewState { attempt: number; water_level_m?: number; poses?: number[]; ropes?: { counts: number[]; points: number[] }; }

const kMostRopePoints = 1024;  // the published state's limit (3072 coordinates)

export class View3D {
  private readonly renderer: THREE.WebGLRenderer;
  private readonly planRenderer: THREE.WebGLRenderer;
  private readonly scene = new THREE.Scene();
  private readonly camera: THREE.PerspectiveCamera;
  private readonly planCamera = new THREE.OrthographicCamera(-50, 50, 50, -50, 1, 2000);
  private readonly controls: OrbitControls;
  private readonly box = new THREE.BoxGeometry(1, 1, 1);
  private readonly cylinder = new THREE.CylinderGeometry(0.5, 0.5, 1, 16).rotateX(Math.PI / 2);  // upright in z
  private readonly materials = new Map<string, THREE.MeshLambertMaterial>();
  private readonly entityGroup = new THREE.Group();
  private readonly ropeGroup = new THREE.Group();
  private readonly bulkGroup = new THREE.Group();
  private bulkQuads = 0;
  private readonly water = new THREE.Mesh(new THREE.PlaneGeometry(3000, 3000),
    new THREE.MeshLambertMaterial({ color: new THREE.Color().setRGB(0.05, 0.16, 0.22, THREE.LinearSRGBColorSpace) }));
  private entities: THREE.Object3D[] = [];
  private names: string[] = [];
  private attempt = -1;
  private station = "";
  private framed = false;
  private dirty = false;
  private nextPlan = 0;
  private readonly labels: CanvasRenderingContext2D;

  constructor(canvas: HTMLCanvasElement, private readonly planCanvas: HTMLCanvasElement,
    private readonly planLabels: HTMLCanvasElement, private readonly looks: Looks) {
    // no multisampling: an instructor's PC may draw it in software (4x the cost)
    this.renderer = new THREE.WebGLRenderer({ canvas, preserveDrawingBuffer: true });
    this.planRenderer = new THREE.WebGLRenderer({ canvas: planCanvas, preserveDrawingBuffer: true });
    this.labels = planLabels.getContext("2d")!;
    this.scene.background = new THREE.Color(0.62, 0.75, 0.88);
    this.scene.add(new THREE.HemisphereLight(0xdde8ff, 0x4a4a40, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(-60, -40, 120);
    this.scene.add(sun);
    this.camera = new THREE.PerspectiveCamera(45, canvas.width / canvas.height, 0.5, 3000);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(-60, -90, 60);
    this.planCamera.up.set(0, 1, 0);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener("change", () => this.invalidate());
    // the quay as the image generator lays it: its top at z = 0, up to its edge at x = 18 m
    const quay = this.block([318, 800, 30], [-141, 0, -15], [0.42, 0.42, 0.40]);
    this.scene.add(quay, this.scenery(), this.water, this.entityGroup, this.ropeGroup, this.bulkGroup);
  }

  /** The station's entities for an attempt (a new attempt replaces them). */
  setScene(m: SceneMessage) {
    this.entityGroup.clear();
    this.bulkGroup.clear();
    this.bulkQuads = 0;
    this.entities = m.entities.map((e, index) => this.entity(e.visual, e.half_m, index));
    for (const e of this.entities) this.entityGroup.add(e);
    this.names = m.entities.map((e) => e.name);
    this.attempt = m.attempt;
    this.station = m.station;
    this.framed = false;
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

  /** Poses and ropes of a state; a state of another attempt than the scene's is not drawn. */
  update(state: ViewState) {
    if (state.attempt !== this.attempt || !state.poses) return;
    const p = state.poses;
    this.entities.forEach((e, n) => {
      const q = p.slice(7 * n, 7 * n + 7);
      e.visible = q.length === 7 && (q[3] !== 0 || q[4] !== 0 || q[5] !== 0 || q[6] !== 0);
      if (!e.visible) return;
      e.position.set(q[0], q[1], q[2]);
      e.quaternion.set(q[3], q[4], q[5], q[6]);
    });
    this.drawRopes(state.ropes);
    if (state.water_level_m !== undefined) this.water.position.z = state.water_level_m;
    if (!this.framed) this.frame();
    this.invalidate();
  }

  // what the browser tests read
  visibleEntities(): number { return this.entities.filter((e) => e.visible).length; }
  bulkQuadsDrawn(): number { return this.bulkQuads; }
  drawnStation(): string { return this.station; }
  cameraPosition(): number[] { return this.camera.position.toArray(); }

  private frame() {
    // the 3D view: the machine (the scene's first entity) whole, from the landside and above; the plan:
    // everything posed
    if (!this.entities.length || !this.entities[0].visible) return;
    const machine = new THREE.Box3().setFromObject(this.entities[0]);
    const centre = machine.getCenter(new THREE.Vector3());
    const reach = Math.max(30, machine.getSize(new THREE.Vector3()).length());
    this.controls.target.copy(centre);
    this.camera.position.set(centre.x - 0.75 * reach, centre.y - 1.0 * reach, centre.z + 0.45 * reach);
    this.controls.update();
    const bounds = new THREE.Box3().setFromObject(this.entityGroup);
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
    this.renderer.render(this.scene, this.camera);
    // the plan at 2 Hz: seen from above, the terminal changes slowly
    const now = performance.now();
    if (now < this.nextPlan) return;
    this.nextPlan = now + 500;
    this.planRenderer.render(this.scene, this.planCamera);
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

  private material(rgb: number[]): THREE.MeshLambertMaterial {
    const key = rgb.map((v) => v.toFixed(3)).join();
    let m = this.materials.get(key);
    if (!m) {
      m = new THREE.MeshLambertMaterial({ color: new THREE.Color().setRGB(rgb[0], rgb[1], rgb[2], THREE.LinearSRGBColorSpace) });
      this.materials.set(key, m);
    }
    return m;
  }

  private block(size: number[], at: number[], rgb: number[], geometry: THREE.BufferGeometry = this.box): THREE.Mesh {
    const mesh = new THREE.Mesh(geometry, this.material(rgb));
    mesh.scale.set(Math.max(size[0], 0.01), Math.max(size[1], 0.01), Math.max(size[2], 0.01));
    mesh.position.set(at[0], at[1], at[2]);
    return mesh;
  }

  // an entity drawn with its look: boxes, lattice girders as their four chords, a mesh as the box it fills;
  // an entity without a look is a grey box of its own size
  private entity(visual: string, half: number[], index: number): THREE.Object3D {
    const group = new THREE.Group();
    const look = this.looks.visuals[visual];
    const own = half.map((h) => 2 * h);
    if (!look) {
      group.add(this.block(own, [0, 0, 0], [0.5, 0.5, 0.5]));
      return group;
    }
    for (const part of look.parts) {
      const size = part.size_m ?? own;
      const rgb = part.livery && look.liveries.length ? look.liveries[index % look.liveries.length] : part.color;
      if (part.shape !== "lattice") { group.add(this.block(size, part.at_m, rgb)); continue; }
      const along = size.indexOf(Math.max(...size));
      for (const a of [-1, 1]) for (const b of [-1, 1]) {
        const chord = size.map((s, k) => (k === along ? s : part.member_m));
        const at = part.at_m.slice();
        const across = [0, 1, 2].filter((k) => k !== along);
        at[across[0]] += a * (size[across[0]] - part.member_m) / 2;
        at[across[1]] += b * (size[across[1]] - part.member_m) / 2;
        group.add(this.block(chord, at, rgb));
      }
    }
    return group;
  }

  private scenery(): THREE.Group {
    const group = new THREE.Group();
    for (const s of this.looks.scenery)
      for (let n = 0; n < s.repeat; ++n) {
        const at = s.at_m.map((v, k) => v + n * s.step_m[k]);
        const size = s.shape === "cylinder" ? [s.size_m[0], s.size_m[0], s.size_m[2]] : s.size_m;
        group.add(this.block(size, at, s.color, s.shape === "cylinder" ? this.cylinder : this.box));
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
