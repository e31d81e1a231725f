// The 3D scene: deck, crane, cable, load and the two ghost markers, placed from one frame.
// Every object lives in a `world` group whose coordinates are the simulation's world frame W
// (North-East-Down, m); the group's matrix turns them into three.js's y-up frame:
// (x, y, z)_NED -> (x, -z, y)_three, a proper rotation.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

// The deck plate (m): 0.6 m along the bow axis, 0.5 m across; the crane base stands 0.225 m to
// port, so the jib reaches out over the port edge and the load hangs clear of the deck.
const DECK = { length: 0.6, width: 0.5, thickness: 0.02 };
const COLOURS = {
  deck: 0x8d99a6,
  tower: 0xe0a526,
  boom: 0xf0b429,
  jib: 0xf7c948,
  joint: 0x3e4c59,
  cable: 0x222222,
  load: 0x1f6feb,
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

export function createScene(container) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  container.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xeef2f6);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8899aa, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  sun.position.set(2, 4, -3);
  scene.add(sun);
  const floor = new THREE.GridHelper(4, 40, 0x9aa5b1, 0xcbd2d9);
  floor.position.y = -1.0; // 1 m below the deck at rest (W z = +1 m)
  scene.add(floor);

  const world = new THREE.Group();
  world.matrixAutoUpdate = false;
  world.matrix.set(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1);
  scene.add(world);

  // The deck in its own frame B (z down): the plate's top face is B's xy plane.
  const deck = new THREE.Group();
  const plate = new THREE.Mesh(new THREE.BoxGeometry(DECK.length, DECK.width, DECK.thickness), material(COLOURS.deck));
  plate.position.z = DECK.thickness / 2;
  deck.add(plate);
  const bow = new THREE.Mesh(new THREE.ConeGeometry(0.03, 0.08, 16), material(0x52606d));
  bow.rotation.z = -Math.PI / 2; // the cone's y axis along B's x: it points to the bow
  bow.position.set(DECK.length / 2 - 0.05, 0, -0.01);
  deck.add(bow);
  world.add(deck);

  const tower = link(COLOURS.tower, 0.014);
  const boom = link(COLOURS.boom, 0.011);
  const jib = link(COLOURS.jib, 0.009);
  const joints = [0, 1, 2].map(() => sphere(COLOURS.joint, 0.016));
  const tip = sphere(COLOURS.joint, 0.012);
  tip.name = "tip";
  const load = sphere(COLOURS.load, 0.03);
  load.name = "load";
  const estimate = sphere(COLOURS.estimate, 0.034, { transparent: true, opacity: 0.35, depthWrite: false });
  estimate.name = "estimated_load";
  const setpoint = new THREE.Mesh(
    new THREE.OctahedronGeometry(0.03),
    new THREE.MeshBasicMaterial({ color: COLOURS.setpoint, wireframe: true }),
  );
  setpoint.name = "setpoint";
  const cableGeometry = new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3()]);
  const cable = new THREE.Line(cableGeometry, new THREE.LineBasicMaterial({ color: COLOURS.cable }));
  for (const object of [tower, boom, jib, ...joints, tip, load, estimate, setpoint, cable]) world.add(object);

  const camera = new THREE.PerspectiveCamera(38, 1, 0.01, 50);
  // From astern and to port, above the deck, looking at the hanging load.
  camera.position.set(-1.05, 0.35, -1.3);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.set(0.0, -0.22, -0.3);
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
    load.position.set(...frames.get("load", i));
    estimate.position.set(...frames.get("estimated_load", i));
    setpoint.position.set(...frames.get("setpoint", i));
    const ends = cableGeometry.attributes.position;
    ends.setXYZ(0, ...points[3]);
    ends.setXYZ(1, ...frames.get("load", i));
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

  // Where an object is drawn on the canvas (drawing-buffer pixels from the top left).
  function onScreen(object) {
    scene.updateMatrixWorld(true);
    const p = object.getWorldPosition(new THREE.Vector3()).project(camera);
    const canvas = renderer.domElement;
    return { x: ((p.x + 1) / 2) * canvas.width, y: ((1 - p.y) / 2) * canvas.height };
  }

  const named = { tip, load, estimated_load: estimate, setpoint };
  return {
    show,
    render,
    resize,
    onScreen: (name) => (named[name] ? onScreen(named[name]) : null),
    drawn: () => ({
      tip: drawn(tip),
      load: drawn(load),
      estimated_load: drawn(estimate),
      setpoint: drawn(setpoint),
    }),
  };
}
