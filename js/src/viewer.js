// The 3D arm view of dhsym: one slider per joint, the DH frames with labels, the arm matrix
// read out live. Bundled with three.js by esbuild (js/package.json) into
// dhsym/view/static/viewer.js as an IIFE named DhsymViewer, so that the page and the widget
// can append the robot's generated functions after it:
//   DhsymViewer.mountPage(element, scene, robot)   a self-contained HTML page
//   DhsymViewer.widget(robot)                      an anywidget module ({ render })
// `scene` is the data dhsym.view.scene writes (joints, base, tool, sizes, entries); `robot`
// the generated functions: robot.fk(q) (world to tool, 16 numbers row by row) and
// robot.links(q) (for each link its matrix A_i, 12 numbers, and the point between the
// row's two halves, 3 numbers). Nothing is fetched: no network, no CDN.
import {
  AmbientLight,
  BoxGeometry,
  BufferGeometry,
  Color,
  CylinderGeometry,
  DirectionalLight,
  Float32BufferAttribute,
  Group,
  Line,
  LineBasicMaterial,
  Matrix4,
  Mesh,
  MeshStandardMaterial,
  PerspectiveCamera,
  Points,
  PointsMaterial,
  Quaternion,
  Scene,
  SphereGeometry,
  Vector3,
  WebGLRenderer,
} from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";
import { CSS2DObject, CSS2DRenderer } from "three/addons/renderers/CSS2DRenderer.js";

const UP = new Vector3(0, 1, 0);
const TRACE = 5000; // points of the tool's path kept
const ELLIPSOID = 0.3; // the manipulability ellipsoid: length units drawn per unit of speed
const STYLE = `
.dhsym-view { font: 13px system-ui, sans-serif; display: flex; flex-wrap: wrap; gap: 12px; color: #222; }
.dhsym-view .stage { position: relative; width: 560px; height: 440px; border: 1px solid #ccc; background: #fafafa; }
.dhsym-view .stage canvas { display: block; }
.dhsym-view .labels { position: absolute; top: 0; left: 0; pointer-events: none; }
.dhsym-view .frame-label { font: 11px monospace; color: #333; background: rgba(255,255,255,0.75); padding: 0 2px; border-radius: 2px; }
.dhsym-view .side { min-width: 300px; max-width: 420px; }
.dhsym-view .slider { display: grid; grid-template-columns: 48px 1fr 96px; align-items: center; gap: 6px; }
.dhsym-view .slider output { font-family: monospace; text-align: right; }
.dhsym-view table.matrix { border-collapse: collapse; font-family: monospace; margin: 6px 0; }
.dhsym-view table.matrix td { padding: 1px 6px; text-align: right; }
.dhsym-view .closed td { text-align: left; font-size: 11px; }
.dhsym-view .links .active { background: #ffe6c7; }
.dhsym-view .buttons { display: flex; flex-wrap: wrap; gap: 4px; margin: 6px 0; }
.dhsym-view .note { color: #a33; }
`;

function el(tag, attrs = {}, text = "") {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text) e.textContent = text;
  return e;
}

// a 4×4 from 16 numbers row by row, or from 12 (the top three rows)
function mat4(a) {
  const m = new Matrix4();
  m.set(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], a[9], a[10], a[11], 0, 0, 0, 1);
  return m;
}

function fmt(x, digits) {
  const v = Math.abs(x) < 0.5 * Math.pow(10, -digits) ? 0 : x;
  return v.toFixed(digits);
}

// A cylinder (or box) from p to q of radius r.
function segment(material, r, box) {
  const geom = box ? new BoxGeometry(2 * r, 1, 2 * r) : new CylinderGeometry(r, r, 1, 16);
  const mesh = new Mesh(geom, material);
  mesh.userData.place = (p, q) => {
    const d = new Vector3().subVectors(q, p);
    const len = d.length();
    mesh.visible = len > 1e-9;
    if (!mesh.visible) return;
    mesh.position.copy(p).addScaledVector(d, 0.5);
    mesh.quaternion.setFromUnitVectors(UP, d.normalize());
    mesh.scale.set(1, len, 1);
  };
  return mesh;
}

// The eigenvalues and unit eigenvectors (columns of V, row by row) of a symmetric 3×3, by
// Jacobi rotations.
export function symmetricEigen(A) {
  const a = [A[0].slice(), A[1].slice(), A[2].slice()];
  const V = [
    [1, 0, 0],
    [0, 1, 0],
    [0, 0, 1],
  ];
  for (let sweep = 0; sweep < 50; sweep++) {
    const off = a[0][1] ** 2 + a[0][2] ** 2 + a[1][2] ** 2;
    if (off < 1e-30) break;
    for (const [p, q] of [
      [0, 1],
      [0, 2],
      [1, 2],
    ]) {
      if (Math.abs(a[p][q]) < 1e-300) continue;
      const theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
      const t = Math.sign(theta || 1) / (Math.abs(theta) + Math.sqrt(theta * theta + 1));
      const c = 1 / Math.sqrt(t * t + 1);
      const s = t * c;
      for (let k = 0; k < 3; k++) {
        const akp = a[k][p];
        const akq = a[k][q];
        a[k][p] = c * akp - s * akq;
        a[k][q] = s * akp + c * akq;
      }
      for (let k = 0; k < 3; k++) {
        const apk = a[p][k];
        const aqk = a[q][k];
        a[p][k] = c * apk - s * aqk;
        a[q][k] = s * apk + c * aqk;
      }
      for (let k = 0; k < 3; k++) {
        const vkp = V[k][p];
        const vkq = V[k][q];
        V[k][p] = c * vkp - s * vkq;
        V[k][q] = s * vkp + c * vkq;
      }
    }
  }
  return { values: [a[0][0], a[1][1], a[2][2]], vectors: V };
}

function axisArrow(color, length, r) {
  const g = new Group();
  const mat = new MeshStandardMaterial({ color });
  const shaft = new Mesh(new CylinderGeometry(r, r, length, 8), mat);
  shaft.position.y = length / 2;
  const tip = new Mesh(new CylinderGeometry(0, 2.2 * r, 4 * r, 12), mat);
  tip.position.y = length + 2 * r;
  g.add(shaft, tip);
  return g;
}

function frameAxes(size, r) {
  const g = new Group();
  const x = axisArrow(0xd62728, size, r);
  x.quaternion.setFromUnitVectors(UP, new Vector3(1, 0, 0));
  const y = axisArrow(0x2ca02c, size, r);
  const z = axisArrow(0x1f77b4, size, r);
  z.quaternion.setFromUnitVectors(UP, new Vector3(0, 0, 1));
  g.add(x, y, z);
  return g;
}

// The view: builds the DOM and the scene, and redraws for a configuration.
class View {
  constructor(root, scene, robot, onChange, ik = null) {
    this.scene = scene;
    this.robot = robot;
    this.onChange = onChange;
    this.n = scene.rows; // DH rows (frames 1 … n); scene.joints: the moving ones
    this.q = scene.joints.map((j) => j.value * j.scale);
    this.active = -1;
    this.redraws = 0;
    root.classList.add("dhsym-view");
    root.appendChild(el("style", {}, STYLE));
    this.buildStage(root);
    this.buildSide(root);
    if (ik) this.buildIK(root.querySelector(".side"), ik);
    this.update();
  }

  // Inverse kinematics (the widget: dhsym solves in Python). The target starts at the tool;
  // the student types its position and turns it about the world axes; the branches come
  // back with their names, or the reason there is none.
  buildIK(side, ik) {
    const box = el("fieldset", { class: "ik" });
    box.appendChild(el("legend", {}, "inverse kinematics: move the target"));
    const fields = {};
    for (const [key, label] of [
      ["x", "x"],
      ["y", "y"],
      ["z", "z"],
      ["rx", "turn about x (°)"],
      ["ry", "turn about y (°)"],
      ["rz", "turn about z (°)"],
    ]) {
      const row = el("label", { class: "slider" });
      row.appendChild(el("span", {}, label));
      const input = el("input", { type: "number", step: "any", "data-target": key });
      input.value = "0";
      row.appendChild(input);
      box.appendChild(row);
      fields[key] = input;
    }
    const solve = el("button", { type: "button", "data-name": "solve" }, "solve");
    const reset = el("button", { type: "button" }, "target at the tool");
    const chooser = el("select", { "data-name": "branches", hidden: "" });
    const reason = el("p", { class: "note", "data-name": "reason" });
    box.append(solve, reset, chooser, reason);
    side.appendChild(box);
    this.target = frameAxes(6 * this.scene.radius, 0.4 * this.scene.radius);
    this.target.matrixAutoUpdate = false;
    this.target.visible = false;
    this.arm.add(this.target);
    const atTool = () => {
      const T = this.robot.fk(this.q);
      fields.x.value = fmt(T[3], 6);
      fields.y.value = fmt(T[7], 6);
      fields.z.value = fmt(T[11], 6);
      for (const k of ["rx", "ry", "rz"]) fields[k].value = "0";
      this.toolAtReset = T;
    };
    atTool();
    reset.addEventListener("click", atTool);
    solve.addEventListener("click", () => {
      const deg = Math.PI / 180;
      const turn = new Matrix4()
        .makeRotationZ(Number(fields.rz.value) * deg)
        .multiply(new Matrix4().makeRotationY(Number(fields.ry.value) * deg))
        .multiply(new Matrix4().makeRotationX(Number(fields.rx.value) * deg));
      const T = turn.multiply(mat4(this.toolAtReset));
      const e = T.clone().transpose().elements; // row by row
      e[3] = Number(fields.x.value);
      e[7] = Number(fields.y.value);
      e[11] = Number(fields.z.value);
      const target = Array.from(e);
      this.target.matrix.copy(mat4(target));
      this.target.visible = true;
      reason.textContent = "solving …";
      ik.solve(target);
      this.draw();
    });
    chooser.addEventListener("change", () => {
      const k = Number(chooser.value);
      if (this.solutions && this.solutions[k]) {
        this.setQ(this.solutions[k].q);
        if (this.onChange) this.onChange(this.q.slice());
      }
    });
    ik.onSolutions((solutions, why) => {
      this.solutions = solutions;
      chooser.replaceChildren(
        ...solutions.map((sol, k) => {
          const o = el("option", { value: String(k) }, sol.branch);
          return o;
        })
      );
      chooser.hidden = solutions.length === 0;
      reason.textContent = solutions.length
        ? `${solutions.length} solution(s): choose a branch`
        : why || "no solution";
      if (solutions.length) {
        chooser.value = "0";
        this.setQ(solutions[0].q);
        if (this.onChange) this.onChange(this.q.slice());
      }
    });
  }

  buildStage(root) {
    const s = this.scene;
    const stage = el("div", { class: "stage" });
    root.appendChild(stage);
    const w = 560;
    const h = 440;
    this.renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setSize(w, h);
    stage.appendChild(this.renderer.domElement);
    this.labels = new CSS2DRenderer();
    this.labels.setSize(w, h);
    this.labels.domElement.className = "labels";
    stage.appendChild(this.labels.domElement);

    this.world = new Scene();
    this.world.background = new Color(0xfafafa);
    // dhsym's z is up: the scene's y is up, so the robot sits in a group turned by -90° about x
    this.arm = new Group();
    this.arm.rotation.x = -Math.PI / 2;
    this.world.add(this.arm);
    this.world.add(new AmbientLight(0xffffff, 0.55));
    const sun = new DirectionalLight(0xffffff, 1.6);
    sun.position.set(2, 4, 3);
    this.world.add(sun);

    const R = s.reach;
    this.camera = new PerspectiveCamera(40, w / h, R / 100, R * 100);
    this.camera.position.set(1.6 * R, 1.3 * R, 2.0 * R);
    this.controls = new OrbitControls(this.camera, this.labels.domElement);
    this.labels.domElement.style.pointerEvents = "auto";
    this.controls.target.set(0, 0.3 * R, 0);
    this.controls.update();
    this.framed = false;
    this.controls.addEventListener("change", () => this.draw());

    const r = s.radius;
    const grey = new MeshStandardMaterial({ color: 0x9a9aa6, metalness: 0.1, roughness: 0.6 });
    const orange = new MeshStandardMaterial({ color: 0xf2801a, metalness: 0.1, roughness: 0.5 });
    this.joints = s.joints.map((j) => segment(orange, 1.6 * r, j.kind === "prismatic"));
    this.links = [];
    for (let i = 0; i <= this.n; i++) this.links.push(segment(grey, r), segment(grey, r));
    this.frames = [];
    this.frameLabels = [];
    for (let i = 0; i <= this.n + 1; i++) {
      const f = frameAxes(4 * r, 0.25 * r);
      f.matrixAutoUpdate = false;
      this.frames.push(f);
      const label = el("span", { class: "frame-label" });
      const obj = new CSS2DObject(label);
      this.frameLabels.push(obj);
      this.arm.add(f, obj);
    }
    this.arm.add(...this.joints, ...this.links);
    const ground = new Group();
    this.arm.add(ground);
    // the workspace, sampled by dhsym with the batched fk
    if (s.cloud && s.cloud.length) {
      const g = new BufferGeometry();
      g.setAttribute("position", new Float32BufferAttribute(s.cloud, 3));
      this.cloud = new Points(g, new PointsMaterial({ color: 0x7777cc, size: r * 0.6 }));
      this.cloud.visible = false;
      this.arm.add(this.cloud);
    }
    this.ellipsoid = new Mesh(
      new SphereGeometry(1, 32, 16),
      new MeshStandardMaterial({ color: 0x3b7dd8, transparent: true, opacity: 0.35 })
    );
    this.ellipsoid.matrixAutoUpdate = false;
    this.ellipsoid.visible = false;
    this.arm.add(this.ellipsoid);
    const path = new BufferGeometry();
    path.setAttribute("position", new Float32BufferAttribute(new Float32Array(3 * TRACE), 3));
    this.traced = 0;
    this.traceLine = new Line(path, new LineBasicMaterial({ color: 0xcc2255 }));
    this.traceLine.frustumCulled = false;
    this.traceLine.visible = false;
    this.arm.add(this.traceLine);
  }

  buildSide(root) {
    const s = this.scene;
    const side = el("div", { class: "side" });
    root.appendChild(side);
    side.appendChild(el("h3", { class: "title" }, s.name));
    this.sliders = s.joints.map((j, i) => {
      const row = el("label", { class: "slider" });
      row.appendChild(el("span", {}, j.name));
      const input = el("input", {
        type: "range",
        min: String(j.min),
        max: String(j.max),
        step: "any",
        "data-joint": String(i + 1),
      });
      input.value = String(j.value);
      const out = el("output", {}, `${fmt(j.value, j.digits)} ${j.unit}`);
      input.addEventListener("input", () => {
        this.q[i] = Number(input.value) * j.scale;
        this.active = i;
        out.textContent = `${fmt(Number(input.value), j.digits)} ${j.unit}`;
        this.update();
        if (this.onChange) this.onChange(this.q.slice());
      });
      row.append(input, out);
      side.appendChild(row);
      return { input, out, joint: j };
    });
    const buttons = el("div", { class: "buttons" });
    side.appendChild(buttons);
    const toggle = (label, on, action) => {
      const b = el("button", { type: "button", "aria-pressed": String(on) }, label);
      b.addEventListener("click", () => {
        const now = b.getAttribute("aria-pressed") !== "true";
        b.setAttribute("aria-pressed", String(now));
        action(now);
        this.draw();
      });
      buttons.appendChild(b);
      return b;
    };
    this.showFrames = true;
    toggle("frames", true, (on) => {
      this.showFrames = on;
      this.update();
    });
    this.closedBox = el("div", { class: "closed", hidden: "" });
    toggle("closed form", false, (on) => {
      this.closedBox.hidden = !on;
    });
    this.linksBox = el("div", { class: "links", hidden: "" });
    toggle("link matrices", false, (on) => {
      this.linksBox.hidden = !on;
    });
    toggle("manipulability", false, (on) => {
      this.ellipsoid.visible = on;
      this.manipulability.hidden = !on;
    });
    toggle("tool path", false, (on) => {
      this.traceLine.visible = on;
    });
    if (this.cloud) toggle("workspace", false, (on) => (this.cloud.visible = on));

    side.appendChild(el("div", {}, `${s.matrix_name} (world to tool)`));
    this.matrix = el("table", { class: "matrix", "data-name": "fk" });
    this.cells = [];
    for (let i = 0; i < 4; i++) {
      const tr = el("tr");
      for (let k = 0; k < 4; k++) {
        const td = el("td");
        tr.appendChild(td);
        this.cells.push(td);
      }
      this.matrix.appendChild(tr);
    }
    side.appendChild(this.matrix);
    this.position = el("div", { class: "position", "data-name": "position" });
    side.appendChild(this.position);
    this.manipulability = el("div", { "data-name": "manipulability", hidden: "" });
    side.appendChild(this.manipulability);

    const closed = el("table", { class: "matrix" });
    for (const row of s.entries) {
      const tr = el("tr");
      for (const e of row) tr.appendChild(el("td", {}, e));
      closed.appendChild(tr);
    }
    this.closedBox.append(el("div", {}, `${s.matrix_name} in closed form`), closed);
    side.appendChild(this.closedBox);
    this.linkTables = [];
    for (let i = 0; i < this.n; i++) {
      const box = el("div", { "data-link": String(i + 1) });
      box.appendChild(el("div", {}, s.link_names[i]));
      const t = el("table", { class: "matrix" });
      const cells = [];
      for (let a = 0; a < 3; a++) {
        const tr = el("tr");
        for (let b = 0; b < 4; b++) {
          const td = el("td");
          tr.appendChild(td);
          cells.push(td);
        }
        t.appendChild(tr);
      }
      box.appendChild(t);
      this.linksBox.appendChild(box);
      this.linkTables.push({ box, cells });
    }
    side.appendChild(this.linksBox);
    if (s.note) side.appendChild(el("p", { class: "note" }, s.note));
  }

  setQ(q) {
    this.q = q.slice();
    this.sliders.forEach(({ input, out, joint }, i) => {
      const v = this.q[i] / joint.scale;
      input.value = String(v);
      out.textContent = `${fmt(v, joint.digits)} ${joint.unit}`;
    });
    this.update();
  }

  update() {
    const s = this.scene;
    const links = this.robot.links(this.q);
    const frames = [mat4(s.base)];
    const elbows = [];
    for (let i = 0; i < this.n; i++) {
      const A = mat4(links[i].slice(0, 12));
      const h = links[i].slice(12, 15);
      elbows.push(new Vector3(h[0], h[1], h[2]).applyMatrix4(frames[i]));
      frames.push(frames[i].clone().multiply(A));
    }
    frames.push(frames[this.n].clone().multiply(mat4(s.tool)));
    const origin = frames.map((F) => new Vector3().setFromMatrixPosition(F));
    const zAxis = frames.map((F) => new Vector3().setFromMatrixColumn(F, 2));
    s.joints.forEach((j, i) => {
      const k = s.convention === "modified" ? j.row + 1 : j.row; // the frame whose z is its axis
      const half = 1.5 * s.radius;
      const p = origin[k].clone().addScaledVector(zAxis[k], -half);
      const q = origin[k].clone().addScaledVector(zAxis[k], half);
      this.joints[i].userData.place(p, q);
    });
    for (let i = 0; i < this.n; i++) {
      this.links[2 * i].userData.place(origin[i], elbows[i]);
      this.links[2 * i + 1].userData.place(elbows[i], origin[i + 1]);
    }
    this.links[2 * this.n].userData.place(origin[this.n], origin[this.n + 1]);
    this.links[2 * this.n + 1].visible = false;
    // frames and their labels; frames at one point share one label ("4, 5, 6")
    const groups = [];
    frames.forEach((F, i) => {
      this.frames[i].matrix.copy(F);
      this.frames[i].matrixWorldNeedsUpdate = true;
      this.frames[i].visible = this.showFrames;
      const g = groups.find((x) => x.at.distanceTo(origin[i]) < 0.2 * s.radius);
      if (g) g.names.push(s.frame_names[i]);
      else groups.push({ at: origin[i], names: [s.frame_names[i]], i });
    });
    this.frameLabels.forEach((obj) => (obj.visible = false));
    for (const g of groups) {
      const obj = this.frameLabels[g.i];
      obj.element.textContent = g.names.join(", ");
      obj.position.copy(g.at).add(new Vector3(0, 0, 1.2 * s.radius));
      obj.visible = this.showFrames;
    }
    // the readout
    const T = this.robot.fk(this.q);
    T.forEach((v, k) => (this.cells[k].textContent = fmt(v, 4)));
    this.position.textContent = `tool at x = ${fmt(T[3], 4)}, y = ${fmt(T[7], 4)}, z = ${fmt(T[11], 4)}`;
    this.position.dataset.xyz = JSON.stringify([T[3], T[7], T[11]]);
    this.linkTables.forEach(({ box, cells }, i) => {
      links[i].slice(0, 12).forEach((v, k) => (cells[k].textContent = fmt(v, 4)));
      box.classList.toggle("active", this.active >= 0 && i === s.joints[this.active].row);
    });
    if (!this.framed) this.frame(origin);
    this.showEllipsoid(T);
    this.record(T);
    this.draw();
  }

  // The manipulability ellipsoid of the tool point: the velocities of joint rates of unit
  // norm, J_v J_vᵀ's eigenvectors scaled by the square roots of its eigenvalues (drawn at
  // ELLIPSOID length units per unit of speed).
  showEllipsoid(T) {
    const n = this.q.length;
    const J = this.robot.jacobian(this.q);
    const A = [0, 1, 2].map((i) =>
      [0, 1, 2].map((k) => {
        let sum = 0;
        for (let j = 0; j < n; j++) sum += J[i * n + j] * J[k * n + j];
        return sum;
      })
    );
    const { values, vectors: V } = symmetricEigen(A);
    const axes = values.map((v) => Math.sqrt(Math.max(v, 0)));
    this.axes = axes;
    this.axisVectors = V;
    const k = ELLIPSOID;
    const m = new Matrix4();
    m.set(
      V[0][0] * axes[0] * k, V[0][1] * axes[1] * k, V[0][2] * axes[2] * k, T[3],
      V[1][0] * axes[0] * k, V[1][1] * axes[1] * k, V[1][2] * axes[2] * k, T[7],
      V[2][0] * axes[0] * k, V[2][1] * axes[1] * k, V[2][2] * axes[2] * k, T[11],
      0, 0, 0, 1
    );
    this.ellipsoid.matrix.copy(m);
    this.ellipsoid.matrixWorldNeedsUpdate = true;
    const w = axes[0] * axes[1] * axes[2];
    this.manipulability.dataset.value = String(w);
    this.manipulability.textContent =
      `manipulability of the tool point √det(J_v J_vᵀ) = ${fmt(w, 5)}; ` +
      `semi-axes ${axes.map((x) => fmt(x, 3)).join(", ")} (per unit joint rate)`;
  }

  // the tool's path: the last TRACE positions, in a buffer made once
  record(T) {
    const pos = this.traceLine.geometry.getAttribute("position");
    if (this.traced < TRACE) {
      pos.setXYZ(this.traced, T[3], T[7], T[11]);
      this.traced += 1;
    } else {
      pos.array.copyWithin(0, 3); // drop the oldest point, keep the line in time order
      pos.setXYZ(TRACE - 1, T[3], T[7], T[11]);
    }
    this.traceLine.geometry.setDrawRange(0, this.traced);
    pos.needsUpdate = true;
  }

  // aim the camera at the arm as it first stands, far enough to see it whole
  frame(origin) {
    this.framed = true;
    const c = new Vector3();
    origin.forEach((p) => c.add(p));
    c.divideScalar(origin.length);
    let size = 0;
    origin.forEach((p) => (size = Math.max(size, p.distanceTo(c))));
    size = Math.max(size, 0.5 * this.scene.reach, 4 * this.scene.radius);
    const target = new Vector3(c.x, c.z, -c.y); // dhsym's z is the scene's y
    const dir = new Vector3(1.0, 0.7, 1.25).normalize();
    this.camera.position.copy(target).addScaledVector(dir, 3.2 * size);
    this.controls.target.copy(target);
    this.controls.update();
  }

  draw() {
    this.renderer.render(this.world, this.camera);
    this.labels.render(this.world, this.camera);
    this.redraws += 1;
    if (this.redraws === 1) this.firstFrame = performance.now(); // ms since the page started
  }
}

// A self-contained page: the view in `element`, for people and for the tests (window.dhsymView).
export function mountPage(element, scene, robot) {
  const view = new View(element, scene, robot, null);
  window.dhsymView = view;
  return view;
}

// The anywidget module: q is shared with Python both ways.
export function widget(robot) {
  return {
    render({ model, el: element }) {
      const scene = model.get("scene");
      const q0 = model.get("q");
      if (q0 && q0.length === scene.joints.length) {
        scene.joints.forEach((j, i) => (j.value = q0[i] / j.scale));
      }
      let answer = null;
      const ik = {
        solve(target) {
          const last = model.get("target") || [];
          if (answer && last.length === 16 && target.every((v, k) => v === last[k])) {
            answer(); // the same target: the answer the kernel gave stands
            return;
          }
          model.set("target", target);
          model.save_changes();
        },
        onSolutions(callback) {
          answer = () => callback(model.get("solutions"), model.get("reason"));
          model.on("change:solved", answer);
        },
      };
      const view = new View(
        element,
        scene,
        robot,
        (q) => {
          model.set("q", q);
          model.save_changes();
        },
        ik
      );
      const onQ = () => {
        const q = model.get("q");
        if (q.some((v, i) => v !== view.q[i])) view.setQ(q);
      };
      model.on("change:q", onQ);
      return () => {
        model.off("change:q", onQ);
        view.controls.dispose();
        view.renderer.dispose();
      };
    },
  };
}
