// The 3D scene: deck, crane (with the full-scale crane's cylinders), cable, load and the two
// ghost markers where the frames have them, placed from one frame.
// Every object lives in a `world` group whose coordinates are the simulation's world frame W
// (North-East-Down, m); the group's matrix turns them into three.js's y-up frame:
// (x, y, z)_NED -> (x, -z, y)_three, a proper rotation.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

// The two cranes' scenes (m), chosen by the page's `scale`.
// - test: the thesis' rig. The deck plate is 0.6 m along the bow axis, 0.5 m across; the crane
//   base stands 0.225 m to port, so the jib reaches out over the port edge and the load hangs
//   clear of the deck.
// - full: the knuckle-boom crane (pedestal 2.2 m, boom 7 m, jib 5.2 m; physics::knuckle_boom)
//   on the 120 m vessel. The deck is the hull's 120 m length and 17 m across (the hull's 15 m
//   breadth widened so that the pedestal, 8 m to port, stands on it); the links are drawn at
//   the column's 0.6 m radius and about half the boom's and jib's box sections; the camera looks
//   from astern and to port at the arm and the load hanging 10 m below its tip.
const LAYOUTS = {
  test: {
    deck: { length: 0.6, width: 0.5, thickness: 0.02 },
    bow: { radius: 0.03, height: 0.08, inset: 0.05 },
    radius: { tower: 0.014, boom: 0.011, jib: 0.009, joint: 0.016, tip: 0.012, load: 0.03, hook: 0.015, estimate: 0.034, setpoint: 0.03 },
    floor: { size: 4, divisions: 40, depth: 1.0 },
    camera: { position: [-1.05, 0.35, -1.3], target: [0.0, -0.22, -0.3], near: 0.01, far: 50 },
  },
  full: {
    deck: { length: 120, width: 17, thickness: 1.0 },
    bow: { radius: 1.5, height: 4, inset: 3 },
    radius: { tower: 0.6, boom: 0.25, jib: 0.2, joint: 0.35, tip: 0.3, load: 0.8, hook: 0.4, estimate: 0.9, setpoint: 0.8, barrel: 0.2, rod: 0.1 },
    floor: { size: 240, divisions: 48, depth: 12 },
    camera: { position: [-20, 10, -32], target: [0, 0, -13], near: 0.5, far: 1000 },
  },
};
const COLOURS = {
  deck: 0x8d99a6,
  tower: 0xe0a526,
  boom: 0xf0b429,
  jib: 0xf7c948,
  joint: 0x3e4c59,
  barrel: 0x52606d,
  rod: 0xcbd2d9,
  cable: 0x222222,
  load: 0x1f6feb,
  hook: 0x3e4c59,
  estimate: 0x2da44e,
  setpoint: 0xd1242f,
};

function material(colour, extra = {}) {
  return new THREE.MeshStandardMaterial({ color: colour, roughness: 0.6, metalness: 0.1, ...extra });
}

// A unit-length cylinder along y, stretched and turned to join two points.
function link(colour, radius) {
  const geometry = new THREE.CylinderGeometry(radius, radius, 1, 16);
  return new THREE.Mesh(geometry, material(colour));
}

const UP = new THREE.Vector3(0, 1, 0);

function placeLink(mesh, from, to) {
  const a = new THREE.Vector3(...from);
  const b = new THREE.Vector3(...to);
  const direction = b.clone().sub(a);
  const length = direction.length();
  mesh.position.copy(a).add(b).multiplyScalar(0.5);
  mesh.scale.set(1, Math.max(length, 1e-9), 1);
  mesh.quaternion.setFromUnitVectors(UP, direction.normalize());
}

function sphere(colour, radius, extra) {
  return new THREE.Mesh(new THREE.SphereGeometry(radius, 24, 16), material(colour, extra));
}

export function createScene(container, scale) {
  const layout = LAYOUTS[scale] || LAYOUTS.test;
  const { deck: plateSize, radius } = layout;
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  container.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xeef2f6);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8899aa, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  sun.position.set(2, 4, -3);
  scene.add(sun);
  const floor = new THREE.GridHelper(layout.floor.size, layout.floor.divisions, 0x9aa5b1, 0xcbd2d9);
  floor.position.y = -layout.floor.depth; // below the deck at rest (W z = +depth)
  scene.add(floor);

  const world = new THREE.Group();
  world.matrixAutoUpdate = false;
  world.matrix.set(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1);
  scene.add(world);

  // The deck in its own frame B (z down): the plate's top face is B's xy plane.
  const deck = new THREE.Group();
  const plate = new THREE.Mesh(new THREE.BoxGeometry(plateSize.length, plateSize.width, plateSize.thickness), material(COLOURS.deck));
  plate.position.z = plateSize.thickness / 2;
  deck.add(plate);
  const bow = new THREE.Mesh(new THREE.ConeGeometry(layout.bow.radius, layout.bow.height, 16), material(0x52606d));
  bow.rotation.z = -Math.PI / 2; // the cone's y axis along B's x: it points to the bow
  bow.position.set(plateSize.length / 2 - layout.bow.inset, 0, -layout.bow.radius / 3);
  deck.add(bow);
  world.add(deck);

  const tower = link(COLOURS.tower, radius.tower);
  const boom = link(COLOURS.boom, radius.boom);
  const jib = link(COLOURS.jib, radius.jib);
  const joints = [0, 1, 2].map(() => sphere(COLOURS.joint, radius.joint));
  const tip = sphere(COLOURS.joint, radius.tip);
  tip.name = "tip";
  // The full-scale crane's boom and jib cylinders: a barrel and a rod each.
  const cylinders = radius.barrel
    ? [0, 1].map(() => ({ barrel: link(COLOURS.barrel, radius.barrel), rod: link(COLOURS.rod, radius.rod) }))
    : [];
  const load = sphere(COLOURS.load, radius.load);
  load.name = "load";
  // A rigging's hook between the hoist rope and the sling (docs/rigging.md), where recorded.
  const hook = sphere(COLOURS.hook, radius.hook);
  hook.name = "hook";
  const estimate = sphere(COLOURS.estimate, radius.estimate, { transparent: true, opacity: 0.35, depthWrite: false });
  estimate.name = "estimated_load";
  const setpoint = new THREE.Mesh(
    new THREE.OctahedronGeometry(radius.setpoint),
    new THREE.MeshBasicMaterial({ color: COLOURS.setpoint, wireframe: true }),
  );
  setpoint.name = "setpoint";
  // The rope from the tip to the hook and the sling on to the load; without a hook the middle
  // point is the load, so the line is the single cable.
  const cableGeometry = new THREE.BufferGeometry().setFromPoints([0, 1, 2].map(() => new THREE.Vector3()));
  const cable = new THREE.Line(cableGeometry, new THREE.LineBasicMaterial({ color: COLOURS.cable }));
  const parts = cylinders.flatMap(({ barrel, rod }) => [barrel, rod]);
  for (const object of [tower, boom, jib, ...joints, tip, ...parts, load, hook, estimate, setpoint, cable]) world.add(object);

  const view = layout.camera;
  const camera = new THREE.PerspectiveCamera(38, 1, view.near, view.far);
  // From astern and to port, above the deck, looking at the hanging load (three.js y-up).
  camera.position.set(...view.position);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.set(...view.target);
  controls.update();

  function resize() {
    const { clientWidth: width, clientHeight: height } = container;
    renderer.setSize(width, height, false);
    renderer.domElement.style.width = "100%";
    renderer.domElement.style.height = "100%";
    camera.aspect = width / Math.max(height, 1);
    camera.updateProjectionMatrix();
  }
  window.addEventListener("resize", resize);
  resize();

  // Places every object for frame i of `frames`.
  function show(frames, i) {
    const [w, x, y, z] = frames.get("deck_attitude", i);
    deck.position.set(...frames.get("deck_position", i));
    deck.quaternion.set(x, y, z, w);
    const crane = frames.get("crane", i);
    const points = [0, 1, 2, 3].map((k) => crane.slice(3 * k, 3 * k + 3));
    placeLink(tower, points[0], points[1]);
    placeLink(boom, points[1], points[2]);
    placeLink(jib, points[2], points[3]);
    joints.forEach((joint, k) => joint.position.set(...points[k]));
    tip.position.set(...points[3]);
    if (frames.has("cylinders")) {
      const pins = frames.get("cylinders", i);
      const point = (k) => pins.slice(3 * k, 3 * k + 3);
      cylinders.forEach(({ barrel, rod }, c) => {
        placeLink(barrel, point(3 * c), point(3 * c + 1));
        placeLink(rod, point(3 * c + 1), point(3 * c + 2));
      });
    }
    load.position.set(...frames.get("load", i));
    hook.visible = frames.has("hook");
    const middle = hook.visible ? frames.get("hook", i) : frames.get("load", i);
    if (hook.visible) hook.position.set(...middle);
    // The ghost markers only where the controller has them.
    for (const [marker, name] of [
      [estimate, "estimated_load"],
      [setpoint, "setpoint"],
    ]) {
      marker.visible = frames.has(name);
      if (marker.visible) marker.position.set(...frames.get(name, i));
    }
    const ends = cableGeometry.attributes.position;
    ends.setXYZ(0, ...points[3]);
    ends.setXYZ(1, ...middle);
    ends.setXYZ(2, ...frames.get("load", i));
    ends.needsUpdate = true;
  }

  function render() {
    renderer.render(scene, camera);
  }

  // The world position (W, NED) of a drawn object, read back from the scene graph.
  function drawn(object) {
    scene.updateMatrixWorld(true);
    const position = object.getWorldPosition(new THREE.Vector3());
    world.worldToLocal(position);
    return [position.x, position.y, position.z];
  }

  // The two ends of a link placed by placeLink (W, NED), read back from the scene graph.
  function ends(mesh) {
    scene.updateMatrixWorld(true);
    return [-0.5, 0.5].map((y) => {
      const position = mesh.localToWorld(new THREE.Vector3(0, y, 0));
      world.worldToLocal(position);
      return [position.x, position.y, position.z];
    });
  }

  // Where an object is drawn on the canvas (drawing-buffer pixels from the top left).
  function onScreen(object) {
    scene.updateMatrixWorld(true);
    const p = object.getWorldPosition(new THREE.Vector3()).project(camera);
    const canvas = renderer.domElement;
    return { x: ((p.x + 1) / 2) * canvas.width, y: ((1 - p.y) / 2) * canvas.height };
  }

  const named = { tip, load, hook, estimated_load: estimate, setpoint };
  // A drawn object's W position, or null when it is not drawn.
  const shown = (object) => (object.visible ? drawn(object) : null);
  return {
    show,
    render,
    resize,
    onScreen: (name) => (named[name]?.visible ? onScreen(named[name]) : null),
    drawn: () => ({
      tip: drawn(tip),
      load: drawn(load),
      hook: shown(hook),
      estimated_load: shown(estimate),
      setpoint: shown(setpoint),
      // The cylinders' barrel pin, barrel end and rod pin (full scale only).
      cylinders: cylinders.length ? cylinders.map(({ barrel, rod }) => ends(barrel).concat(ends(rod))) : null,
      canvas: { width: renderer.domElement.width, height: renderer.domElement.height },
    }),
  };
}
