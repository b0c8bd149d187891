/* rigidblocks 3D report view: blocks, joint forces, loads and the collapse mechanism.
 *
 * window.rbViewer(THREE, data, root, table) builds the view inside the element root
 * from the data written by rigidblocks.reporting.view3d. Everything is merged into a few
 * buffers (one mesh for all blocks, one set of lines for their edges, one for the
 * mechanism's marks, one for the force shafts, one instanced cone for the heads), and
 * frames are drawn only when something changes, so that a wall of thousands of blocks
 * stays responsive. Mouse: drag to turn, wheel to zoom, right-drag or shift-drag to
 * pan; hover a joint's dot for its forces.
 */
(function () {
  "use strict";

  function decode(s, T) {
    const bin = atob(s || "");
    const buf = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) buf[i] = bin.charCodeAt(i);
    return new T(buf.buffer);
  }

  function esc(s) {
    return String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;");
  }

  function fmt(x) {
    if (x === null || x === undefined) return "-";
    if (x === "inf") return "\u221e";
    const a = Math.abs(x);
    if (a !== 0 && (a < 1e-3 || a >= 1e5)) return x.toExponential(3);
    return String(Number(x.toPrecision(4)));
  }

  // rigid motion of block i at amplitude s (see plot3d.displaced_vertices):
  // p' = R p + t with R = exp(s [w]x), t = c - R c + V s u
  function motion(vel, cen, i, s, out) {
    const ux = s * vel[6 * i], uy = s * vel[6 * i + 1], uz = s * vel[6 * i + 2];
    const wx = s * vel[6 * i + 3], wy = s * vel[6 * i + 4], wz = s * vel[6 * i + 5];
    const th = Math.sqrt(wx * wx + wy * wy + wz * wz);
    let a, b, c2;
    if (th < 1e-9) { a = 1; b = 0.5; c2 = 0; } else {
      a = Math.sin(th) / th; b = (1 - Math.cos(th)) / (th * th);
      c2 = (th - Math.sin(th)) / (th * th * th);
    }
    // K = [w]x, K2 = K K
    const K = [0, -wz, wy, wz, 0, -wx, -wy, wx, 0];
    const K2 = [
      -(wy * wy + wz * wz), wx * wy, wx * wz,
      wx * wy, -(wx * wx + wz * wz), wy * wz,
      wx * wz, wy * wz, -(wx * wx + wy * wy)];
    const R = new Array(9), V = new Array(9);
    for (let k = 0; k < 9; k++) {
      const I = (k % 4 === 0) ? 1 : 0;
      R[k] = I + a * K[k] + b * K2[k];
      V[k] = I + b * K[k] + c2 * K2[k];
    }
    if (th < 1e-9) for (let k = 0; k < 9; k++) { R[k] = ((k % 4 === 0) ? 1 : 0) + K[k]; }
    const cx = cen[3 * i], cy = cen[3 * i + 1], cz = cen[3 * i + 2];
    for (let r = 0; r < 3; r++) {
      out[12 * i + 3 * r] = R[3 * r]; out[12 * i + 3 * r + 1] = R[3 * r + 1];
      out[12 * i + 3 * r + 2] = R[3 * r + 2];
      out[12 * i + 9 + r] = (r === 0 ? cx : r === 1 ? cy : cz)
        - (R[3 * r] * cx + R[3 * r + 1] * cy + R[3 * r + 2] * cz)
        + (V[3 * r] * ux + V[3 * r + 1] * uy + V[3 * r + 2] * uz);
    }
  }

  function apply(T, i, src, dst, j) {
    const x = src[j], y = src[j + 1], z = src[j + 2], o = 12 * i;
    dst[j] = T[o] * x + T[o + 1] * y + T[o + 2] * z + T[o + 9];
    dst[j + 1] = T[o + 3] * x + T[o + 4] * y + T[o + 5] * z + T[o + 10];
    dst[j + 2] = T[o + 6] * x + T[o + 7] * y + T[o + 8] * z + T[o + 11];
  }

  window.rbViewer = function (THREE, D, root, table) {
    const t0 = performance.now();
    const canvas = root.querySelector("canvas");
    const tip = root.querySelector(".rb-tip");
    const labelsBox = root.querySelector(".rb-labels");
    // multisampling triples the cost of a frame without a GPU (software WebGL): large
    // scenes go without it, their edges drawn anyway
    const renderer = new THREE.WebGLRenderer({ canvas: canvas,
      antialias: D.n_triangles < 20000, preserveDrawingBuffer: true });
    renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    const scene = new THREE.Scene();
    scene.background = new THREE.Color(0xf6f5f0);
    const size = D.size;
    const lo = D.lo, hi = D.hi;
    const centre = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2,
      (lo[2] + hi[2]) / 2);
    const radius0 = 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    const camera = new THREE.PerspectiveCamera(35, 1, radius0 * 0.01, radius0 * 200);
    camera.up.set(0, 0, 1);
    scene.add(camera);
    scene.add(new THREE.AmbientLight(0xffffff, 1.1));
    const sun = new THREE.DirectionalLight(0xffffff, 2.2);
    sun.position.set(-0.4, -0.6, 1.0);
    camera.add(sun);
    const sky = new THREE.DirectionalLight(0xffffff, 0.8);
    sky.position.set(0.3, 0.5, 1.0);
    scene.add(sky);

    // -- blocks ------------------------------------------------------------------
    const n = D.n_blocks;
    const pos0 = decode(D.positions, Float32Array);
    const vstart = decode(D.vstart, Uint32Array);
    const cen = decode(D.centroids, Float32Array);
    const pos = new Float32Array(pos0);
    const posAttr = new THREE.BufferAttribute(pos, 3);
    const M = D.mechanism || null;
    const colours = new Float32Array(pos.length);
    const cFree = new THREE.Color(0xd9c7a7), cSup = new THREE.Color(0x8a8a8a),
      cMove = new THREE.Color(0xe39a5b);
    for (let i = 0; i < n; i++) {
      const c = D.support[i] ? cSup : (M && M.moving[i] ?
        (M.colours && M.colours[i] ? new THREE.Color(M.colours[i]) : cMove) : cFree);
      for (let v = vstart[i]; v < vstart[i + 1]; v++) {
        colours[3 * v] = c.r; colours[3 * v + 1] = c.g; colours[3 * v + 2] = c.b;
      }
    }
    const geo = new THREE.BufferGeometry();
    geo.setAttribute("position", posAttr);
    geo.setAttribute("color", new THREE.BufferAttribute(colours, 3));
    geo.setIndex(new THREE.BufferAttribute(decode(D.triangles, Uint32Array), 1));
    const blockMat = new THREE.MeshPhongMaterial({ vertexColors: true, flatShading: true,
      shininess: 0, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1,
      polygonOffsetUnits: 1 });
    const mesh = new THREE.Mesh(geo, blockMat);
    mesh.frustumCulled = false;
    const edgeGeo = new THREE.BufferGeometry();
    edgeGeo.setAttribute("position", posAttr);
    edgeGeo.setIndex(new THREE.BufferAttribute(decode(D.edges, Uint32Array), 1));
    const edges = new THREE.LineSegments(edgeGeo, new THREE.LineBasicMaterial({
      color: 0x222222, transparent: true, opacity: n > 2000 ? 0.15 : 0.7 }));
    edges.frustumCulled = false;
    // the original position, shown as faint edges while the mechanism is displaced
    const ghostGeo = new THREE.BufferGeometry();
    ghostGeo.setAttribute("position", new THREE.BufferAttribute(pos0, 3));
    ghostGeo.setIndex(edgeGeo.index);
    const ghost = new THREE.LineSegments(ghostGeo, new THREE.LineBasicMaterial({
      color: 0x777777, transparent: true, opacity: 0.35 }));
    ghost.frustumCulled = false;
    // large scenes: while the view moves (drag, wheel, play) their edges are left out,
    // which halves a frame's cost without a GPU; the still view has them again
    const big = D.n_triangles > 20000;
    let liteTimer = null;
    function lite(on) {
      if (!big) return;
      edges.visible = !on;
      ghostHidden = on;
      ghost.visible = !on && ghostWanted;
      if (!on) request();
    }
    let ghostHidden = false, ghostWanted = false;
    const layers = { blocks: new THREE.Group(), forces: new THREE.Group(),
      mechanism: new THREE.Group(), loads: new THREE.Group(), joints: new THREE.Group() };
    layers.blocks.add(mesh, edges);
    for (const k in layers) scene.add(layers[k]);

    // -- joints: dots to hover, forces ----------------------------------------------
    const J = D.joints || null;
    let jointDots = null, jPairs = null, jPts = null, jStart = null;
    if (J) {
      jPairs = decode(J.pairs, Uint32Array);
      jPts = decode(J.points, Float32Array);
      jStart = decode(J.start, Uint32Array);
      const cg = new THREE.BufferGeometry();
      cg.setAttribute("position", new THREE.BufferAttribute(decode(J.centres, Float32Array), 3));
      // drawn through the blocks (joints are mostly inside), faint: where to hover
      jointDots = new THREE.Points(cg, new THREE.PointsMaterial({ color: 0x1b4f72,
        size: J.n > 3000 ? 2 : 4, sizeAttenuation: false, depthTest: false,
        transparent: true, opacity: 0.45 }));
      jointDots.renderOrder = 4;
      jointDots.frustumCulled = false;
      layers.joints.add(jointDots);
      if (J.breached) {  // a check that fails: the joints it breaches, red
        const idx = decode(J.breached, Uint32Array), cen = decode(J.centres, Float32Array);
        const pos = new Float32Array(3 * idx.length);
        for (let i = 0; i < idx.length; i++)
          for (let k = 0; k < 3; k++) pos[3 * i + k] = cen[3 * idx[i] + k];
        const bg = new THREE.BufferGeometry();
        bg.setAttribute("position", new THREE.BufferAttribute(pos, 3));
        const breached = new THREE.Points(bg, new THREE.PointsMaterial({ color: 0xd62728,
          size: 10, sizeAttenuation: false, depthTest: false }));
        breached.renderOrder = 5;
        breached.frustumCulled = false;
        layers.joints.add(breached);
      }
      if (J.forces) {
        const at = decode(J.forces.at, Float32Array), vec = decode(J.forces.vec, Float32Array);
        const m = at.length / 3;
        const shaft = new Float32Array(6 * m);
        const heads = new THREE.InstancedMesh(new THREE.ConeGeometry(1, 1, 10),
          new THREE.MeshPhongMaterial({ color: 0x1f77b4, shininess: 0 }), m);
        const up = new THREE.Vector3(0, 1, 0), d = new THREE.Vector3(),
          q = new THREE.Quaternion(), s = new THREE.Vector3(), p = new THREE.Vector3(),
          mat4 = new THREE.Matrix4();
        for (let k = 0; k < m; k++) {
          const L = Math.hypot(vec[3 * k], vec[3 * k + 1], vec[3 * k + 2]);
          const h = Math.min(0.3 * L, 0.035 * size);
          d.set(vec[3 * k] / L, vec[3 * k + 1] / L, vec[3 * k + 2] / L);
          for (let c = 0; c < 3; c++) {
            shaft[6 * k + c] = at[3 * k + c];
            shaft[6 * k + 3 + c] = at[3 * k + c] + vec[3 * k + c] - d.getComponent(c) * h;
          }
          q.setFromUnitVectors(up, d);
          p.set(at[3 * k] + vec[3 * k] - d.x * h / 2, at[3 * k + 1] + vec[3 * k + 1] - d.y * h / 2,
            at[3 * k + 2] + vec[3 * k + 2] - d.z * h / 2);
          s.set(0.35 * h, h, 0.35 * h);
          mat4.compose(p, q, s);
          heads.setMatrixAt(k, mat4);
        }
        heads.frustumCulled = false;
        const sg = new THREE.BufferGeometry();
        sg.setAttribute("position", new THREE.BufferAttribute(shaft, 3));
        const shafts = new THREE.LineSegments(sg, new THREE.LineBasicMaterial({ color: 0x1f77b4 }));
        shafts.frustumCulled = false;
        layers.forces.add(shafts, heads);
      }
    }
    const highlight = new THREE.LineLoop(new THREE.BufferGeometry(),
      new THREE.LineBasicMaterial({ color: 0xd81b60, depthTest: false }));
    highlight.renderOrder = 10;
    highlight.frustumCulled = false;
    scene.add(highlight);

    // -- loads ----------------------------------------------------------------------
    const labels = [];
    for (const L of D.loads || []) {
      const a = new THREE.Vector3().fromArray(L.tail), b = new THREE.Vector3().fromArray(L.tip);
      const len = a.distanceTo(b);
      const colour = L.live ? 0xc2185b : 0x333333;
      const arrow = new THREE.ArrowHelper(b.clone().sub(a).normalize(), a, len, colour,
        0.18 * len, 0.08 * len);
      // on top of the blocks: the resultants act at the centre of gravity, inside them
      arrow.traverse(function (o) {
        if (o.material) { o.material.depthTest = false; o.material.transparent = true; }
        o.renderOrder = 6;
      });
      layers.loads.add(arrow);
      const el = document.createElement("div");
      el.className = "rb-label " + (L.live ? "live" : "dead");
      el.textContent = L.label;
      labelsBox.appendChild(el);
      labels.push({ el: el, at: L.kind === "point load" ? a : b });
    }

    // -- mechanism --------------------------------------------------------------------
    let vel = null, segP0 = null, segP = null, segBlock = null, segLines = null;
    const T = new Float32Array(12 * n);
    const slider = root.querySelector("input.rb-amp");
    if (M) {
      vel = decode(M.velocities, Float32Array);
      segP0 = decode(M.segments, Float32Array);
      segP = new Float32Array(segP0);
      segBlock = decode(M.segment_block, Uint32Array);
      const kinds = decode(M.segment_kind, Uint32Array);
      const segCol = new Float32Array(segP.length);
      const kc = [new THREE.Color(0xd62728), new THREE.Color(0x1f77b4), new THREE.Color(0xff8c00)];
      for (let s = 0; s < kinds.length; s++) {
        for (let e = 0; e < 2; e++) {
          const c = kc[kinds[s]];
          segCol[6 * s + 3 * e] = c.r; segCol[6 * s + 3 * e + 1] = c.g;
          segCol[6 * s + 3 * e + 2] = c.b;
        }
      }
      const g = new THREE.BufferGeometry();
      g.setAttribute("position", new THREE.BufferAttribute(segP, 3));
      g.setAttribute("color", new THREE.BufferAttribute(segCol, 3));
      segLines = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ vertexColors: true,
        depthTest: false, transparent: true, opacity: 0.95 }));
      segLines.renderOrder = 5;
      segLines.frustumCulled = false;
      // hinge lines also as large dots at their ends (lines are one pixel wide)
      const hingeIdx = [];
      for (let s = 0; s < kinds.length; s++) if (kinds[s] === 0) hingeIdx.push(2 * s, 2 * s + 1);
      const hg = new THREE.BufferGeometry();
      hg.setAttribute("position", g.getAttribute("position"));
      hg.setIndex(hingeIdx);
      const hingeDots = new THREE.Points(hg, new THREE.PointsMaterial({ color: 0xd62728,
        size: 7, sizeAttenuation: false, depthTest: false }));
      hingeDots.renderOrder = 6;
      hingeDots.frustumCulled = false;
      layers.mechanism.add(segLines, hingeDots, ghost);
    }
    let amplitude = M ? 1 : 0;
    function displace(t) {
      if (!M) return;
      const s = t * M.scale;
      for (let i = 0; i < n; i++) motion(vel, cen, i, s, T);
      for (let i = 0; i < n; i++) {
        for (let v = vstart[i]; v < vstart[i + 1]; v++) apply(T, i, pos0, pos, 3 * v);
      }
      for (let k = 0; k < segBlock.length; k++) apply(T, segBlock[k], segP0, segP, 3 * k);
      posAttr.needsUpdate = true;
      segLines.geometry.attributes.position.needsUpdate = true;
      ghostWanted = t > 0;
      ghost.visible = ghostWanted && !ghostHidden;
    }

    // -- camera and controls ------------------------------------------------------------
    const target = centre.clone();
    let az = -Math.PI / 2 - 0.6, el = 0.45, dist = 0.95 * radius0 / Math.sin(35 * Math.PI / 360);
    const dist0 = dist;
    function place() {
      const ce = Math.cos(el);
      camera.position.set(target.x + dist * ce * Math.cos(az), target.y + dist * ce * Math.sin(az),
        target.z + dist * Math.sin(el));
      camera.lookAt(target);
      camera.updateMatrixWorld();
    }
    let pending = false;
    function render() {
      place();
      renderer.render(scene, camera);
      const w = canvas.clientWidth, h = canvas.clientHeight;
      const v = new THREE.Vector3();
      for (const L of labels) {
        v.copy(L.at).project(camera);
        const show = layers.loads.visible && v.z < 1;
        L.el.style.display = show ? "block" : "none";
        L.el.style.left = ((v.x + 1) / 2 * w) + "px";
        L.el.style.top = ((1 - v.y) / 2 * h) + "px";
      }
    }
    function request() {
      if (pending) return;
      pending = true;
      requestAnimationFrame(function () { pending = false; render(); });
    }
    function resize() {
      const w = canvas.clientWidth || 800, h = canvas.clientHeight || 500;
      renderer.setSize(w, h, false);
      camera.aspect = w / h;
      camera.updateProjectionMatrix();
      request();
    }
    let drag = null, playing = false;
    canvas.addEventListener("pointerdown", function (e) {
      drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
      canvas.setPointerCapture(e.pointerId);
      lite(true);
    });
    canvas.addEventListener("pointerup", function (e) {
      drag = null;
      canvas.releasePointerCapture(e.pointerId);
      if (!playing) lite(false);
    });
    canvas.addEventListener("contextmenu", function (e) { e.preventDefault(); });
    canvas.addEventListener("pointermove", function (e) {
      if (drag) {
        const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
        drag.x = e.clientX; drag.y = e.clientY;
        if (drag.pan) {
          const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
          const upv = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1);
          const k = dist * 0.0015;
          target.addScaledVector(right, -dx * k).addScaledVector(upv, dy * k);
        } else {
          az -= dx * 0.008;
          el = Math.max(-1.5, Math.min(1.5, el + dy * 0.008));
        }
        tip.hidden = true;
        request();
      } else {
        hover(e);
      }
    });
    canvas.addEventListener("wheel", function (e) {
      e.preventDefault();
      dist *= Math.exp(e.deltaY * 0.001);
      dist = Math.max(dist0 * 0.02, Math.min(dist0 * 20, dist));
      lite(true);
      clearTimeout(liteTimer);
      liteTimer = setTimeout(function () { if (!drag && !playing) lite(false); }, 250);
      request();
    }, { passive: false });

    // -- hover: a joint's forces ----------------------------------------------------------
    const ray = new THREE.Raycaster();
    ray.params.Points.threshold = 0.012 * size;
    const mouse = new THREE.Vector2();
    let hoverPending = null;
    function showJoint(k, x, y) {
      const a = jPairs[2 * k], b = jPairs[2 * k + 1];
      const pts = [];
      for (let p = jStart[k]; p < jStart[k + 1]; p++) {
        pts.push(new THREE.Vector3(jPts[3 * p], jPts[3 * p + 1], jPts[3 * p + 2]));
      }
      highlight.geometry.setFromPoints(pts);
      highlight.visible = true;
      let html = "<b>joint " + esc(D.ids[a]) + " \u2013 " + esc(D.ids[b]) + "</b>";
      if (table && table.n) {
        const fu = D.units.force ? " " + D.units.force : "";
        const lu = D.units.length ? " " + D.units.length : "";
        if (table.has_forces) {
          html += "<br>N = " + fmt(table.N[k]) + fu + ", |T| = " + fmt(table.T[k]) + fu +
            "<br>e = " + fmt(table.e[k]) + lu + ", |T|/N = " + fmt(table.demand[k]);
        }
        html += "<br>state: " + esc(table.state[k]);
        if (table.governing[k]) html += " (governing)";
      }
      tip.innerHTML = html;
      if (x !== undefined) {
        tip.style.left = (x + 14) + "px";
        tip.style.top = (y + 10) + "px";
      }
      tip.hidden = false;
      request();
    }
    function hover(e) {
      if (!jointDots) return;  // the dots need not be shown to be found
      const r = canvas.getBoundingClientRect();
      hoverPending = { x: e.clientX - r.left, y: e.clientY - r.top };
      requestAnimationFrame(function () {
        if (!hoverPending) return;
        const h = hoverPending;
        hoverPending = null;
        mouse.set(h.x / r.width * 2 - 1, -(h.y / r.height) * 2 + 1);
        ray.setFromCamera(mouse, camera);
        const hit = ray.intersectObject(jointDots, false);
        if (hit.length) {
          showJoint(hit[0].index, h.x, h.y);
        } else if (!tip.hidden) {
          tip.hidden = true;
          highlight.visible = false;
          request();
        }
      });
    }

    // -- controls panel -------------------------------------------------------------------
    for (const box of root.querySelectorAll("input[data-layer]")) {
      const name = box.getAttribute("data-layer");
      // thousands of joint dots veil the blocks: shown on request only
      if (name === "joints" && J && J.n > 3000) box.checked = false;
      if (!layers[name] || (name === "mechanism" && !M) || (name === "forces" &&
          !(J && J.forces)) || (name === "joints" && !J)) {
        box.disabled = true;
        box.checked = false;
        box.parentElement.classList.add("off");
      }
      if (layers[name]) layers[name].visible = box.checked;
      box.addEventListener("change", function () {
        layers[name].visible = box.checked;
        if (name === "forces") look();
        if (name === "mechanism") {
          displace(box.checked ? amplitude : 0);
          if (slider) slider.disabled = !box.checked;
        }
        request();
      });
    }
    const play = root.querySelector("button.rb-play");
    if (slider) {
      slider.disabled = !M;
      slider.value = String(Math.round(amplitude * 1000));
      slider.addEventListener("change", function () { if (!playing) lite(false); });
      slider.addEventListener("input", function () {
        lite(true);
        amplitude = Number(slider.value) / 1000;
        if (layers.mechanism.visible) displace(amplitude);
        request();
      });
    }
    if (play) {
      play.disabled = !M;
      play.addEventListener("click", function () {
        playing = !playing;
        play.textContent = playing ? "pause" : "play";
        lite(playing);
        const start = performance.now();
        (function step(now) {
          if (!playing) return;
          const ph = ((now - start) / 2500) % 2;
          amplitude = ph < 1 ? ph : 2 - ph;
          if (slider) slider.value = String(Math.round(amplitude * 1000));
          if (layers.mechanism.visible) displace(amplitude);
          render();
          requestAnimationFrame(step);
        })(start);
      });
    }
    const reset = root.querySelector("button.rb-reset");
    if (reset) {
      reset.addEventListener("click", function () {
        target.copy(centre); az = -Math.PI / 2 - 0.6; el = 0.45; dist = dist0; request();
      });
    }
    window.rbHighlightJoint = function (k) {
      if (!J) return;
      const c = decode(J.centres, Float32Array);
      const v = new THREE.Vector3(c[3 * k], c[3 * k + 1], c[3 * k + 2]).project(camera);
      const w = canvas.clientWidth, h = canvas.clientHeight;
      showJoint(k, (v.x + 1) / 2 * w, (1 - v.y) / 2 * h);
      root.scrollIntoView({ block: "nearest" });
    };

    // with the forces on, the blocks turn see-through: most joints are inside
    function look() {
      const see = layers.forces.visible && !!(J && J.forces);
      blockMat.transparent = see;
      blockMat.opacity = see ? 0.35 : 1;
      blockMat.depthWrite = !see;
      blockMat.needsUpdate = true;
    }
    look();
    if (M && layers.mechanism.visible) displace(amplitude);
    if (typeof ResizeObserver !== "undefined") new ResizeObserver(resize).observe(canvas);
    resize();
    render();
    const gl = renderer.getContext();
    const px = new Uint8Array(4);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const info = renderer.info.render;
    const stats = document.documentElement.dataset;
    // the share of the canvas not painted in the background colour (a blank view: 0)
    const W = gl.drawingBufferWidth, H = gl.drawingBufferHeight;
    const all = new Uint8Array(4 * W * H);
    gl.readPixels(0, 0, W, H, gl.RGBA, gl.UNSIGNED_BYTE, all);
    const hex = scene.background.getHex();  // sRGB, as painted
    const br = (hex >> 16) & 255, bgg = (hex >> 8) & 255, bb = hex & 255;
    let painted = 0;
    for (let k = 0; k < all.length; k += 4) {
      if (Math.abs(all[k] - br) + Math.abs(all[k + 1] - bgg) + Math.abs(all[k + 2] - bb) > 12) {
        painted++;
      }
    }
    stats.viewerPainted = (painted / (W * H)).toFixed(4);
    stats.viewerReady = "1";
    stats.viewerBuildMs = (performance.now() - t0).toFixed(1);
    stats.viewerFirstFrameMs = performance.now().toFixed(1);
    stats.viewerTriangles = String(info.triangles);
    stats.viewerDrawCalls = String(info.calls);
    if (location.hash.indexOf("rb-bench") >= 0) bench(gl, px);
    if (location.hash.indexOf("rb-selftest") >= 0) selftest();

    // every control once, as a user would (#rb-selftest in the address): errors go to
    // the page's error hook, the hover's text to data-selftest-tip
    function selftest() {
      for (const box of root.querySelectorAll("input[data-layer]")) {
        if (box.disabled) continue;
        box.checked = !box.checked; box.dispatchEvent(new Event("change"));
        box.checked = !box.checked; box.dispatchEvent(new Event("change"));
      }
      if (slider && !slider.disabled) {
        slider.value = "500"; slider.dispatchEvent(new Event("input"));
      }
      if (play && !play.disabled) { play.click(); play.click(); }
      if (reset) reset.click();
      if (J) window.rbHighlightJoint(0);
      const row = document.querySelector("#rb-table tbody tr");
      if (row) row.click();
      const th = document.querySelector("#rb-table th");
      if (th) th.click();
      render();
      stats.selftestTip = tip.hidden ? "" : tip.textContent;
      stats.selftest = "done";
    }

    // timing of interaction, for the benchmark (#rb-bench in the address)
    function bench(gl, px) {
      const frames = 20;
      lite(true);  // as while dragging or playing
      let t = performance.now();
      for (let k = 0; k < frames; k++) {
        az += 0.05; render(); gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
      }
      stats.benchRotateMs = ((performance.now() - t) / frames).toFixed(2);
      if (M) {
        t = performance.now();
        for (let k = 0; k < frames; k++) {
          displace(k / frames); render();
          gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
        }
        stats.benchSliderMs = ((performance.now() - t) / frames).toFixed(2);
        displace(amplitude);
      }
      lite(false);
      t = performance.now();
      render(); gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
      stats.benchStillMs = (performance.now() - t).toFixed(2);
      if (jointDots) {
        t = performance.now();
        mouse.set(0.1, 0.1);
        for (let k = 0; k < frames; k++) {
          ray.setFromCamera(mouse, camera); ray.intersectObject(jointDots, false);
        }
        stats.benchHoverMs = ((performance.now() - t) / frames).toFixed(2);
      }
    }
  };
})();
