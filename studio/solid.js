/**
 * The 3D view of `noncirc cad`'s solids: every part meshed once by the wasm module (the
 * STL's triangles, coarser), each copy placed at the carrier angle as `noncirc cad` places
 * it, drawn by three.js (vendored in vendor/, MIT; loaded when the view first opens).
 * Drag turns the view, the wheel zooms.
 */

/** A colour per kind of part (the copy's name without its number), as docs/cad.md's figure. */
const COLOURS = {
  sun: 0x8c9aa8, intermediate: 0x6f8fb3, intermediate_b: 0x5a7ca3, planet: 0x9fb4c8,
  carrier_plate: 0xd9d2c3, arm: 0xd08a3c, pusher: 0xb5532c, driver: 0x8c9aa8, driven: 0x6f8fb3,
};

/** The chord tolerance of the view's meshes (mm): the files keep 1 µm. */
const VIEW_CHORD_MM = 0.01;

/**
 * Opens the view of `design`'s solids on `canvas` (after `design.solidParts()`, which
 * `parts` holds). Returns `{ place(carrierDeg), placements, parts, dispose() }`.
 */
export async function openSolidView(design, parts, canvas) {
  const THREE = await import('./vendor/three.module.min.js');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(canvas.clientWidth || 520, canvas.clientHeight || 420, false);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xffffff);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x556677, 1.6));
  const light = new THREE.DirectionalLight(0xffffff, 1.8);
  light.position.set(0.4, -0.5, 0.75);
  scene.add(light);
  const geometries = parts.map((_, i) => {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(design.solidMesh(i, VIEW_CHORD_MM), 3));
    g.computeVertexNormals();
    return g;
  });
  const materials = parts.map((p) => {
    const plate = p.name === 'carrier_plate';
    return new THREE.MeshStandardMaterial({
      color: COLOURS[p.name] ?? 0x999999, metalness: 0.25, roughness: 0.55,
      transparent: plate, opacity: plate ? 0.28 : 1, depthWrite: !plate, side: plate ? THREE.DoubleSide : THREE.FrontSide,
    });
  });
  const model = new THREE.Group();
  scene.add(model);
  const camera = new THREE.PerspectiveCamera(30, 1, 1, 1e5);
  camera.up.set(0, 0, 1);
  const view = { azimuth: -60, elevation: 35, distance: 1, centre: new THREE.Vector3() };
  let meshes = [];
  let placements = [];

  function render() {
    const az = view.azimuth * Math.PI / 180;
    const el = view.elevation * Math.PI / 180;
    const d = view.distance;
    camera.position.set(view.centre.x + d * Math.cos(el) * Math.cos(az), view.centre.y + d * Math.cos(el) * Math.sin(az), view.centre.z + d * Math.sin(el));
    camera.lookAt(view.centre);
    const { width, height } = canvas.getBoundingClientRect();
    camera.aspect = width > 0 && height > 0 ? width / height : 520 / 420;
    camera.updateProjectionMatrix();
    renderer.render(scene, camera);
  }

  function place(carrierDeg) {
    placements = JSON.parse(design.solidPlacements(carrierDeg));
    if (meshes.length !== placements.length) {
      model.clear();
      meshes = placements.map((p) => {
        const m = new THREE.Mesh(geometries[p.part], materials[p.part]);
        m.name = p.name;
        model.add(m);
        return m;
      });
    }
    placements.forEach((p, i) => {
      meshes[i].position.set(p.at_mm[0], p.at_mm[1], p.at_mm[2]);
      meshes[i].rotation.set(0, 0, p.angle_deg * Math.PI / 180);
    });
    render();
  }

  place(0);
  // Frame the assembly once, about its bounding sphere.
  const sphere = new THREE.Box3().setFromObject(model).getBoundingSphere(new THREE.Sphere());
  view.centre.copy(sphere.center);
  // The assembly is flat: its sphere is wider than it looks from above, so come closer.
  view.distance = sphere.radius / Math.sin((camera.fov / 2) * Math.PI / 180) * 0.75;

  let drag = null;
  const down = (ev) => { drag = { x: ev.clientX, y: ev.clientY }; canvas.setPointerCapture(ev.pointerId); };
  const move = (ev) => {
    if (!drag) return;
    view.azimuth -= (ev.clientX - drag.x) * 0.4;
    view.elevation = Math.max(-89, Math.min(89, view.elevation + (ev.clientY - drag.y) * 0.4));
    drag = { x: ev.clientX, y: ev.clientY };
    render();
  };
  const up = () => { drag = null; };
  const wheel = (ev) => { ev.preventDefault(); view.distance *= Math.exp(ev.deltaY * 0.001); render(); };
  canvas.addEventListener('pointerdown', down);
  canvas.addEventListener('pointermove', move);
  canvas.addEventListener('pointerup', up);
  canvas.addEventListener('wheel', wheel, { passive: false });

  return {
    parts,
    place,
    get placements() { return placements; },
    /** Triangles drawn (each copy's), for the tests. */
    get triangles() { return meshes.reduce((n, m) => n + m.geometry.attributes.position.count / 3, 0); },
    dispose() {
      canvas.removeEventListener('pointerdown', down);
      canvas.removeEventListener('pointermove', move);
      canvas.removeEventListener('pointerup', up);
      canvas.removeEventListener('wheel', wheel);
      geometries.forEach((g) => g.dispose());
      materials.forEach((m) => m.dispose());
      renderer.dispose();
    },
  };
}
