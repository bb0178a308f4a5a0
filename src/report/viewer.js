// SPDX-License-Identifier: MIT
// The WebGL view of a genflow report: the meshes of the page's data block, orbit controls,
// a checkbox per mesh, a colouring and a layout. It sets body[data-status] to "drawn" after the
// first frame and body[data-error] on any error, which the browser test reads.
(function () {
  'use strict';

  const body = document.body;
  const errorBanner = document.getElementById('viewer-error');

  function fail(message) {
    body.dataset.error = String(message);
    errorBanner.textContent = 'The view could not be drawn: ' + message;
    errorBanner.hidden = false;
  }
  window.addEventListener('error', function (event) { fail(event.message); });

  // The data block's arrays are little-endian base64, as every browser's platform reads them.
  function bytesOf(base64) {
    const text = atob(base64);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) {
      bytes[i] = text.charCodeAt(i);
    }
    return bytes;
  }
  function floatsOf(base64) { return new Float32Array(bytesOf(base64).buffer); }
  function indicesOf(base64) { return new Uint32Array(bytesOf(base64).buffer); }

  const PLAIN = '';
  const PLAIN_GREY = 190;  // of 255: light enough that shading shows the shape

  function plainColors(count) {
    return new Uint8Array(3 * count).fill(PLAIN_GREY);
  }

  function buildMesh(entry) {
    const geometry = new THREE.BufferGeometry();
    const positions = floatsOf(entry.positions);
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    geometry.setIndex(new THREE.BufferAttribute(indicesOf(entry.indices), 1));
    geometry.computeVertexNormals();
    geometry.computeBoundingBox();
    const count = positions.length / 3;
    const colorings = {};
    for (const name in entry.colorings) {
      colorings[name] = bytesOf(entry.colorings[name]);
    }
    colorings[PLAIN] = plainColors(count);
    geometry.setAttribute('color', new THREE.BufferAttribute(colorings[PLAIN].slice(), 3, true));
    const material = new THREE.MeshLambertMaterial({
      vertexColors: THREE.VertexColors,
      side: THREE.DoubleSide,
    });
    const mesh = new THREE.Mesh(geometry, material);
    mesh.visible = entry.shown;
    return { name: entry.name, mesh: mesh, colorings: colorings, box: geometry.boundingBox };
  }

  function startView(data) {
    const holder = document.getElementById('viewer');
    let renderer;
    try {
      renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    } catch (error) {
      holder.textContent = 'This browser cannot draw WebGL; the plots and tables below still hold.';
      body.dataset.status = 'no-webgl';
      return;
    }
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    holder.appendChild(renderer.domElement);

    const scene = new THREE.Scene();
    scene.background = new THREE.Color(0xffffff);
    const camera = new THREE.PerspectiveCamera(35, 1, 1e-3, 1e3);
    scene.add(camera);
    scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 0.55));
    const headlight = new THREE.DirectionalLight(0xffffff, 0.5);
    headlight.position.set(0.3, 0.5, 1);
    camera.add(headlight);

    const meshes = data.meshes.map(buildMesh);
    meshes.forEach(function (m) { scene.add(m.mesh); });
    const controls = new THREE.OrbitControls(camera, renderer.domElement);
    const state = { coloring: data.default_coloring, layout: 'side' };

    function render() {
      renderer.render(scene, camera);
      body.dataset.status = 'drawn';
    }
    controls.addEventListener('change', render);

    function resize() {
      const width = holder.clientWidth;
      const height = holder.clientHeight;
      renderer.setSize(width, height);
      camera.aspect = width / Math.max(height, 1);
      camera.updateProjectionMatrix();
      render();
    }

    // Side by side: the shown meshes in a row along x, a tenth of the largest extent apart;
    // overlaid: each where its coordinates put it.
    function placeMeshes() {
      const shown = meshes.filter(function (m) { return m.mesh.visible; });
      let largest = 0;
      shown.forEach(function (m) {
        largest = Math.max(largest, m.box.getSize(new THREE.Vector3()).length());
      });
      let x = 0;
      shown.forEach(function (m) {
        if (state.layout === 'side') {
          m.mesh.position.set(x - m.box.min.x, 0, 0);
          x += m.box.max.x - m.box.min.x + 0.1 * largest;
        } else {
          m.mesh.position.set(0, 0, 0);
        }
      });
    }

    function frameShown() {
      const box = new THREE.Box3();
      meshes.forEach(function (m) {
        if (m.mesh.visible) {
          box.union(m.box.clone().translate(m.mesh.position));
        }
      });
      if (box.isEmpty()) {
        return;
      }
      const center = box.getCenter(new THREE.Vector3());
      const size = box.getSize(new THREE.Vector3());
      // Far enough that the box's front face fits the view both ways, with a margin of a tenth.
      const halfHeight = Math.tan((camera.fov * Math.PI) / 360);
      const distance = 1.1 * Math.max(size.y / 2 / halfHeight,
        size.x / 2 / (halfHeight * camera.aspect)) + size.z / 2 + 1e-9;
      camera.near = distance / 100;
      camera.far = distance * 100;
      camera.position.copy(center).add(new THREE.Vector3(0, 0, distance));
      camera.updateProjectionMatrix();
      controls.target.copy(center);
      controls.update();
    }

    function applyColoring() {
      meshes.forEach(function (m) {
        const colors = m.colorings[state.coloring] || m.colorings[PLAIN];
        const attribute = m.mesh.geometry.getAttribute('color');
        attribute.array.set(colors);
        attribute.needsUpdate = true;
      });
      const legend = document.getElementById('legend');
      const scale = data.colorings.find(function (c) { return c.name === state.coloring; });
      legend.hidden = !scale || scale.top === undefined;
      if (!legend.hidden) {
        document.getElementById('legend-bar').style.background = scale.gradient;
        document.getElementById('legend-top').textContent = scale.top_text;
        document.getElementById('legend-name').textContent = scale.name;
      }
    }

    function buildControls() {
      const toggles = document.getElementById('mesh-toggles');
      meshes.forEach(function (m) {
        const label = document.createElement('label');
        const box = document.createElement('input');
        box.type = 'checkbox';
        box.checked = m.mesh.visible;
        box.addEventListener('change', function () {
          m.mesh.visible = box.checked;
          placeMeshes();
          frameShown();
          render();
        });
        label.appendChild(box);
        label.appendChild(document.createTextNode(' ' + m.name));
        toggles.appendChild(label);
      });
      const select = document.getElementById('coloring');
      [{ name: PLAIN, label: 'plain' }].concat(data.colorings.map(function (c) {
        return { name: c.name, label: c.name };
      })).forEach(function (c) {
        const option = document.createElement('option');
        option.value = c.name;
        option.textContent = c.label;
        option.selected = c.name === state.coloring;
        select.appendChild(option);
      });
      select.addEventListener('change', function () {
        state.coloring = select.value;
        applyColoring();
        render();
      });
      document.querySelectorAll('input[name=layout]').forEach(function (radio) {
        radio.addEventListener('change', function () {
          state.layout = radio.value;
          placeMeshes();
          frameShown();
          render();
        });
      });
    }

    // The page's address ending in #view shows the view alone, filling the window (with its
    // controls and scale): for a large view, and for pictures of it.
    function applyHash() {
      body.classList.toggle('view-only', window.location.hash === '#view');
      resize();
      frameShown();
      render();
    }

    buildControls();
    applyColoring();
    placeMeshes();
    // A new window size frames the meshes anew: the old framing may cut them off.
    window.addEventListener('resize', function () {
      resize();
      frameShown();
      render();
    });
    window.addEventListener('hashchange', applyHash);
    applyHash();
  }

  try {
    startView(JSON.parse(document.getElementById('genflow-report-data').textContent));
  } catch (error) {
    fail(error && error.message ? error.message : error);
  }
})();
