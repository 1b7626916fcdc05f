// The three.js side of the light-update benchmark (bench/web_lights_bench.mjs), loaded
// into the client's page next to app.js: the same emitters (sphere, disc, rect, torus) as
// unlit meshes in a three.js scene, rendered by a CubeCamera into a float
// WebGLCubeRenderTarget and projected by LightProbeGenerator.fromCubeRenderTarget (order 3,
// the only order three.js has). Its own canvas and WebGL2 context. Exposes window.threeBench.
import * as THREE from 'three';
import { LightProbeGenerator } from 'three/addons/lights/LightProbeGenerator.js';
import { torusMesh } from './torus_mesh.js';

const canvas = document.createElement('canvas');
canvas.width = canvas.height = 16;
canvas.style.display = 'none';
document.body.appendChild(canvas);
const renderer = new THREE.WebGLRenderer({ canvas, antialias: false });
renderer.toneMapping = THREE.NoToneMapping;

let scene = null, cubeCamera = null, target = null;

// Emitted radiance (linear) as an unlit colour: three.js writes it unchanged into a float target.
function material(light, side) {
  const k = light.intensity ?? 1, c = light.color ?? [1, 1, 1];
  const m = new THREE.MeshBasicMaterial({ side });
  m.color.setRGB(c[0] * k, c[1] * k, c[2] * k, THREE.LinearSRGBColorSpace);
  return m;
}

// One-sided flat emitters face +z in three.js; turn +z onto the light's normal.
function facing(mesh, normal) {
  const n = new THREE.Vector3(...normal).normalize();
  mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), n);
}

function emitterMesh(light) {
  let mesh;
  if (light.shape === 'sphere') {
    mesh = new THREE.Mesh(new THREE.SphereGeometry(light.radius, 64, 32), material(light, THREE.FrontSide));
  } else if (light.shape === 'disc') {
    mesh = new THREE.Mesh(new THREE.CircleGeometry(light.radius, 64), material(light, THREE.FrontSide));
    facing(mesh, light.normal ?? [0, -1, 0]);
  } else if (light.shape === 'rect') {
    mesh = new THREE.Mesh(new THREE.PlaneGeometry(light.size[0], light.size[1]), material(light, THREE.FrontSide));
    facing(mesh, light.normal ?? [0, -1, 0]);
  } else {
    const { positions, indices } = torusMesh();
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    g.setIndex(new THREE.BufferAttribute(indices, 1));
    mesh = new THREE.Mesh(g, material(light, THREE.DoubleSide));  // mesh lights are two-sided
    mesh.scale.setScalar(light.scale ?? 1);
  }
  mesh.position.set(...light.position);
  return mesh;
}

window.threeBench = {
  revision: THREE.REVISION,
  // Builds the emitters and a size^2-per-face float cube target at centre c.
  setup(lights, centre, size) {
    if (target) target.dispose();
    scene = new THREE.Scene();
    scene.background = new THREE.Color(0, 0, 0);
    for (const l of lights) scene.add(emitterMesh(l));
    target = new THREE.WebGLCubeRenderTarget(size, { type: THREE.FloatType, format: THREE.RGBAFormat, generateMipmaps: false });
    cubeCamera = new THREE.CubeCamera(0.01, 1000, target);
    cubeCamera.position.set(...centre);
    scene.add(cubeCamera);
  },
  // One light update the three.js way: cube render + LightProbeGenerator (async readback).
  async update() {
    cubeCamera.update(renderer, scene);
    return LightProbeGenerator.fromCubeRenderTarget(renderer, target);
  },
  // n updates; milliseconds of each. With `syncReadback`, the renderer's
  // readRenderTargetPixelsAsync is swapped for the synchronous readRenderTargetPixels while
  // timing: LightProbeGenerator then runs its own code unchanged, minus the fence polling
  // (setTimeout(4) per face until the GPU process reports the fence signalled).
  async time(n, { syncReadback = false } = {}) {
    const asyncRead = renderer.readRenderTargetPixelsAsync;
    if (syncReadback) {
      renderer.readRenderTargetPixelsAsync = async (rt, x, y, w, h, buffer, face) => {
        renderer.readRenderTargetPixels(rt, x, y, w, h, buffer, face);
        return buffer;
      };
    }
    try {
      const samples = [];
      for (let i = 0; i < n; i++) {
        const t0 = performance.now();
        await this.update();
        samples.push(performance.now() - t0);
      }
      return samples;
    } finally {
      renderer.readRenderTargetPixelsAsync = asyncRead;
    }
  },
  // A lower bound on any CPU projection in three.js: the cube render plus a synchronous
  // readRenderTargetPixels of the six faces, with no SH work at all.
  timeRenderAndReadback(n) {
    const size = target.width, pixels = new Float32Array(size * size * 4);
    const samples = [];
    for (let i = 0; i < n; i++) {
      const t0 = performance.now();
      cubeCamera.update(renderer, scene);
      for (let f = 0; f < 6; f++) renderer.readRenderTargetPixels(target, 0, 0, size, size, pixels, f);
      samples.push(performance.now() - t0);
    }
    return samples;
  },
  // The order-3 SH (9 rows of [r, g, b], radiance) of the current emitters.
  async sh() {
    const probe = await this.update();
    return probe.sh.coefficients.map((v) => [v.x, v.y, v.z]);
  },
};
