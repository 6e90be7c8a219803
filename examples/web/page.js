// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The page's side (docs/web.md): the scenario picker and buttons, an orbit camera, mouse picking
// (a ray into the world, the body held by a joint at the pointer), and WebGL drawing of the vertex
// arrays xeno_web.cpp fills through the library's DebugDraw. window.xenoPage is what the
// headless-browser test (test_page.py) drives.
"use strict";

var Module = {
  onRuntimeInitialized: function () { xenoPage.start(); },
  print: function (text) { console.log(text); },
  printErr: function (text) { console.error(text); },
};

const xenoPage = (function () {
  const canvas = document.getElementById("view");
  const gl = canvas.getContext("webgl", { antialias: true, preserveDrawingBuffer: true });
  const ui = {
    scene: document.getElementById("scene"), play: document.getElementById("play"),
    step: document.getElementById("step"), restart: document.getElementById("restart"),
    contacts: document.getElementById("contacts"), bench: document.getElementById("bench"),
    stats: document.getElementById("stats"),
  };
  const state = { scene: 0, precision: 1, playing: true, ready: false, camera: null, frames: 0, benchmark: "" };

  // --- camera: orbit about a target (yaw, pitch, distance), perspective 45° ------------------
  function cameraFromScene() {
    const eye = [0, 1, 2].map((k) => Module._xw_camera(k));
    const target = [3, 4, 5].map((k) => Module._xw_camera(k));
    const d = [eye[0] - target[0], eye[1] - target[1], eye[2] - target[2]];
    const distance = Math.hypot(d[0], d[1], d[2]);
    state.camera = { target, distance, yaw: Math.atan2(d[0], d[2]), pitch: Math.asin(d[1] / distance) };
  }
  function eyePosition() {
    const c = state.camera;
    return [c.target[0] + c.distance * Math.cos(c.pitch) * Math.sin(c.yaw), c.target[1] + c.distance * Math.sin(c.pitch),
            c.target[2] + c.distance * Math.cos(c.pitch) * Math.cos(c.yaw)];
  }
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const unit = (a) => { const l = Math.hypot(a[0], a[1], a[2]); return [a[0] / l, a[1] / l, a[2] / l]; };
  function basis() {  // forward, right, up of the camera
    const forward = unit(sub(state.camera.target, eyePosition()));
    const right = unit(cross(forward, [0, 1, 0]));
    return { forward, right, up: cross(right, forward) };
  }
  const fovY = 45 * Math.PI / 180;
  function viewProjection() {  // column-major 4×4 for WebGL
    const eye = eyePosition(), { forward: f, right: r, up: u } = basis();
    const aspect = canvas.width / canvas.height, t = 1 / Math.tan(fovY / 2), near = 0.05, far = 500;
    const view = [r[0], u[0], -f[0], 0, r[1], u[1], -f[1], 0, r[2], u[2], -f[2], 0,
                  -dot(r, eye), -dot(u, eye), dot(f, eye), 1];
    const proj = [t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0];
    const out = new Array(16).fill(0);
    for (let c = 0; c < 4; ++c)
      for (let r2 = 0; r2 < 4; ++r2)
        for (let k = 0; k < 4; ++k) out[c * 4 + r2] += proj[k * 4 + r2] * view[c * 4 + k];
    return new Float32Array(out);
  }
  function rayThrough(x, y) {  // pixel (CSS px in the canvas) → world ray
    const rect = canvas.getBoundingClientRect();
    const nx = 2 * (x - rect.left) / rect.width - 1, ny = 1 - 2 * (y - rect.top) / rect.height;
    const { forward: f, right: r, up: u } = basis(), t = Math.tan(fovY / 2), aspect = canvas.width / canvas.height;
    return { origin: eyePosition(), direction: unit([0, 1, 2].map((k) => f[k] + r[k] * nx * t * aspect + u[k] * ny * t)) };
  }

  // --- WebGL: lit triangles and plain lines --------------------------------------------------
  function program(vs, fs) {
    const p = gl.createProgram();
    for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
      const s = gl.createShader(type);
      gl.shaderSource(s, src);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      gl.attachShader(p, s);
    }
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
    return p;
  }
  const lit = program(
    "attribute vec3 p; attribute vec3 n; attribute vec4 c; uniform mat4 m; uniform float alpha; varying vec4 v;" +
    "void main() { gl_Position = m * vec4(p, 1.0); vec3 l = normalize(vec3(0.4, 1.0, 0.6));" +
    " float d = 0.35 + 0.65 * max(dot(normalize(n), l), 0.0); v = vec4(c.rgb * d, c.a * alpha); }",
    "precision mediump float; varying vec4 v; void main() { gl_FragColor = v; }");
  const plain = program(
    "attribute vec3 p; attribute vec4 c; uniform mat4 m; uniform float alpha; varying vec4 v;" +
    "void main() { gl_Position = m * vec4(p, 1.0); v = vec4(c.rgb, c.a * alpha); }",
    "precision mediump float; varying vec4 v; void main() { gl_FragColor = v; }");
  const buffer = gl.createBuffer();

  function drawArrays(prog, pointer, floats, stride, layout, mode, alpha, matrix) {
    if (floats === 0) return;
    gl.useProgram(prog);
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.bufferData(gl.ARRAY_BUFFER, Module.HEAPF32.subarray(pointer / 4, pointer / 4 + floats), gl.STREAM_DRAW);
    for (const [name, size, offset] of layout) {
      const at = gl.getAttribLocation(prog, name);
      gl.enableVertexAttribArray(at);
      gl.vertexAttribPointer(at, size, gl.FLOAT, false, stride * 4, offset * 4);
    }
    gl.uniformMatrix4fv(gl.getUniformLocation(prog, "m"), false, matrix);
    gl.uniform1f(gl.getUniformLocation(prog, "alpha"), alpha);
    gl.drawArrays(mode, 0, floats / stride);
  }
  function drawWorld(precision, alpha, matrix) {
    const triangles = Module._xw_draw(precision, ui.contacts.checked ? 1 : 0);
    drawArrays(lit, Module._xw_triangles(precision), triangles * 10, 10, [["p", 3, 0], ["n", 3, 3], ["c", 4, 6]], gl.TRIANGLES,
               alpha, matrix);
    drawArrays(plain, Module._xw_lines(precision), Module._xw_line_vertices(precision) * 7, 7, [["p", 3, 0], ["c", 4, 3]],
               gl.LINES, alpha, matrix);
  }
  function render() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== w || canvas.height !== h) canvas.width = w, canvas.height = h;
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(0.16, 0.18, 0.22, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    const m = viewProjection();
    if (state.precision >= 1) drawWorld(1, 1, m);
    if (state.precision === 0) drawWorld(0, 1, m);
    if (state.precision === 2) drawWorld(0, 0.45, m);  // float translucent over double
    state.frames++;
  }

  // --- numbers -------------------------------------------------------------------------------
  function showStats() {
    const p = state.precision === 0 ? 0 : 1;
    let text = `t ${Module._xw_time().toFixed(2)} s (story ${Module._xw_camera(6).toFixed(1)} s)   ${Module._xw_step_ms().toFixed(2)} ms/step   ` +
               `bodies ${Module._xw_stat(p, 0)}   contacts ${Module._xw_stat(p, 1)}   awake ${Module._xw_stat(p, 2)}`;
    if (state.precision === 2) text += `   largest float-double position difference ${Module._xw_max_difference().toExponential(2)} m`;
    if (state.benchmark) text += "\n" + state.benchmark;
    ui.stats.textContent = text;
  }

  // --- scenes and buttons --------------------------------------------------------------------
  function load(scene, precision) {
    if (scene !== undefined) state.scene = scene;
    if (precision !== undefined) state.precision = precision;
    if (Module._xw_load(state.scene, state.precision) !== 0)
      throw new Error("xw_load failed: " + Module.UTF8ToString(Module._xw_error()));
    ui.scene.value = String(state.scene);
    document.querySelector(`input[name=precision][value="${state.precision}"]`).checked = true;
    cameraFromScene();
    render();
    showStats();
  }
  function stepOnce() { Module._xw_step(1); render(); showStats(); }
  function benchmark() {  // the 210-box pyramid, 100 steps, sleeping off, float and double, best of 3 (as native_bench.cpp)
    const pyramid = sceneIndex("pyramid");
    let f = Infinity, d = Infinity;
    for (let run = 0; run < 3; ++run)
      f = Math.min(f, Module._xw_benchmark(pyramid, 0, 100)), d = Math.min(d, Module._xw_benchmark(pyramid, 1, 100));
    state.benchmark = `pyramid (210 boxes), 100 steps, best of 3: float ${f.toFixed(2)} ms/step, double ${d.toFixed(2)} ms/step (WebAssembly)`;
    console.log("xeno benchmark: " + state.benchmark);
    showStats();
    return { float: f, double: d };
  }
  function sceneIndex(name) {
    for (let i = 0; i < Module._xw_scene_count(); ++i) if (Module.UTF8ToString(Module._xw_scene_name(i)) === name) return i;
    return -1;
  }
  function tick() {
    if (state.playing) Module._xw_step(1);
    render();
    if (state.frames % 10 === 0 || !state.playing) showStats();
    requestAnimationFrame(tick);
  }

  // --- mouse: pick and drag, or orbit; wheel zooms -------------------------------------------
  let mouse = null;
  canvas.addEventListener("mousedown", (e) => {
    const ray = rayThrough(e.clientX, e.clientY);
    const o = ray.origin, d = ray.direction;
    if (e.button === 0 && Module._xw_pick(o[0], o[1], o[2], d[0], d[1], d[2])) {
      const grab = [0, 1, 2].map((k) => Module._xw_grab_point(k));
      mouse = { grab: true, depth: dot(sub(grab, o), basis().forward) };
    } else mouse = { grab: false, x: e.clientX, y: e.clientY };
  });
  window.addEventListener("mousemove", (e) => {
    if (!mouse) return;
    if (mouse.grab) {  // the pointer's point at the grab's depth from the camera
      const ray = rayThrough(e.clientX, e.clientY);
      const along = mouse.depth / dot(ray.direction, basis().forward);
      const p = [0, 1, 2].map((k) => ray.origin[k] + ray.direction[k] * along);
      Module._xw_drag(p[0], p[1], p[2]);
    } else {
      state.camera.yaw -= (e.clientX - mouse.x) * 0.01;
      state.camera.pitch = Math.max(-1.45, Math.min(1.45, state.camera.pitch + (e.clientY - mouse.y) * 0.01));
      mouse.x = e.clientX, mouse.y = e.clientY;
    }
  });
  window.addEventListener("mouseup", () => { if (mouse && mouse.grab) Module._xw_release(); mouse = null; });
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    state.camera.distance = Math.max(0.5, state.camera.distance * Math.exp(e.deltaY * 0.001));
  }, { passive: false });

  function start() {
    for (let i = 0; i < Module._xw_scene_count(); ++i) {
      const option = document.createElement("option");
      option.value = String(i);
      option.textContent = Module.UTF8ToString(Module._xw_scene_name(i)) + ": " + Module.UTF8ToString(Module._xw_scene_description(i));
      ui.scene.appendChild(option);
    }
    ui.scene.addEventListener("change", () => load(Number(ui.scene.value)));
    ui.play.addEventListener("click", () => { state.playing = !state.playing; ui.play.textContent = state.playing ? "pause" : "play"; });
    ui.step.addEventListener("click", () => { state.playing = false; ui.play.textContent = "play"; stepOnce(); });
    ui.restart.addEventListener("click", () => load());
    ui.bench.addEventListener("click", () => benchmark());
    for (const radio of document.querySelectorAll("input[name=precision]"))
      radio.addEventListener("change", () => load(undefined, Number(radio.value)));
    const query = new URLSearchParams(location.search);
    if (query.has("paused")) state.playing = false, ui.play.textContent = "play";
    const named = query.has("scene") ? sceneIndex(query.get("scene")) : -1;
    load(named >= 0 ? named : sceneIndex("pyramid"), query.has("precision") ? Number(query.get("precision")) : 1);
    state.ready = true;
    requestAnimationFrame(tick);
  }

  return {
    start, load, stepOnce, benchmark, sceneIndex, render,
    get ready() { return state.ready; },
    get state() { return state; },
    setPlaying(on) { state.playing = on; ui.play.textContent = on ? "pause" : "play"; },
  };
})();
