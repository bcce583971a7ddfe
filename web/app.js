// millpath in the browser. This one module is both the page's controller and, loaded again
// as a module Web Worker, the planner: the engine (pkg/, built by scripts/web) runs in the
// worker, so a long plan never freezes the page. What the engine returns is shown as it
// comes: the program's bytes offered for download unchanged, the report's figures, the
// preview SVG and the HTML report (viewer with playback) the CLI's --html writes.
//
// URL parameters (all optional):
//   ?plan=sample:aerospace&strategy=auto&depth=5   plan a sample at load with these flags
//   &hold=URL&release=URL                           load an image from hold (which holds the
//                                                   load event), POST to release once the
//                                                   result is drawn (a headless browser's
//                                                   screenshot, taken at load, waits for it)
//   ?selftest=URL    run the cases listed at URL (JSON: [{id, name, url?, options}]) through
//                    the page, POST each offered program to URL/../result/ID and what the
//                    page showed to .../ID.json, then POST .../done

import init, * as engine from "./pkg/millpath_web.js";

const inWorker = typeof window === "undefined";

if (inWorker) {
  worker();
} else {
  page();
}

// ---------------------------------------------------------------- the worker: the engine

function worker() {
  let ready = null;
  self.onmessage = async (event) => {
    const job = event.data;
    try {
      if (!ready) {
        ready = init().then(() => engine.install_panic_hook());
      }
      await ready;
      if (job.kind === "meta") {
        self.postMessage({ id: job.id, ok: true, machines: engine.machines(), version: engine.version() });
        return;
      }
      const options = JSON.stringify(job.options);
      if (job.kind === "list") {
        const pockets = engine.list(job.bytes, job.name, options);
        self.postMessage({ id: job.id, ok: true, pockets });
        return;
      }
      self.postMessage({ id: job.id, stage: "planning, verifying on the stock simulation, timing" });
      const t0 = performance.now();
      const run = engine.pocket(job.bytes, job.name, options);
      const planMs = performance.now() - t0;
      try {
        const gcode = run.gcode();
        const report = JSON.parse(run.report());
        const notes = run.notes();
        const pockets = run.pockets();
        self.postMessage({ id: job.id, stage: "drawing the report" });
        const t1 = performance.now();
        const preview = run.preview();
        const html = run.html();
        const drawMs = performance.now() - t1;
        self.postMessage(
          { id: job.id, ok: true, gcode, report, notes, pockets, preview, html, planMs, drawMs },
          [gcode.buffer],
        );
      } finally {
        run.free();
      }
    } catch (e) {
      // A refusal is an Error carrying the engine's message; anything else (a trap after a
      // panic) leaves the module unusable: say so, and let the page start a new worker.
      const refused = e instanceof Error && !(e instanceof WebAssembly.RuntimeError);
      const message = refused
        ? e.message
        : `internal error: the engine stopped (${e}); it is loaded anew for the next plan`;
      self.postMessage({ id: job.id, ok: false, message, fatal: !refused });
      if (!refused) self.close();
    }
  };
}

// ---------------------------------------------------------------- the page

function page() {
  const $ = (id) => document.getElementById(id);
  const params = new URLSearchParams(location.search);
  let drawing = { name: $("sample").value, bytes: null };
  let planner = null;
  let nextId = 1;
  const waiting = new Map();
  let downloadUrl = null;

  function startWorker() {
    planner = new Worker(new URL(import.meta.url), { type: "module" });
    planner.onmessage = (event) => {
      const m = event.data;
      const w = waiting.get(m.id);
      if (!w) return;
      if (m.stage) {
        w.onStage(m.stage);
        return;
      }
      waiting.delete(m.id);
      if (m.fatal) planner = null;
      w.resolve(m);
    };
    planner.onerror = (event) => {
      for (const w of waiting.values()) {
        w.resolve({ ok: false, fatal: true, message: `internal error: the engine could not run (${event.message})` });
      }
      waiting.clear();
      planner = null;
    };
  }

  // Sends a job to the worker; resolves with its answer.
  function ask(job, onStage = () => {}) {
    if (!planner) startWorker();
    const id = nextId++;
    return new Promise((resolve) => {
      waiting.set(id, { resolve, onStage });
      const transfer = job.bytes ? [job.bytes.slice().buffer] : [];
      const bytes = job.bytes ? new Uint8Array(transfer[0]) : undefined;
      planner.postMessage({ ...job, id, bytes }, transfer);
    });
  }

  // The options as the CLI's flags: every form field with a data-flag and a value.
  function options() {
    const o = {};
    for (const el of document.querySelectorAll("[data-flag]")) {
      const v = el.value.trim();
      if (v !== "") o[el.dataset.flag] = v;
    }
    return o;
  }

  function setOptions(o) {
    for (const el of document.querySelectorAll("[data-flag]")) {
      if (o[el.dataset.flag] !== undefined) el.value = String(o[el.dataset.flag]);
    }
  }

  function command(name, o) {
    const quote = (s) => (/^[\w.:,+\/-]+$/.test(s) ? s : `'${s.replaceAll("'", "'\\''")}'`);
    const flags = Object.entries(o).map(([k, v]) => (v === true ? `--${k}` : `--${k} ${quote(String(v))}`));
    return ["millpath pocket", quote(name), ...flags].join(" ");
  }

  function showError(message) {
    $("error").textContent = `error: ${message}`;
    $("error").hidden = false;
  }

  function clearResults() {
    $("error").hidden = true;
    $("error").textContent = "";
    $("outcome").hidden = true;
  }

  function showFound(pockets, notes) {
    const list = (ul, items) => {
      ul.replaceChildren(...items.map((t) => Object.assign(document.createElement("li"), { textContent: t })));
    };
    list($("pockets"), pockets || []);
    list($("notes"), (notes || []).map((n) => `note: ${n}`));
    $("found").hidden = !(pockets && pockets.length);
  }

  const extension = { linuxcnc: "ngc", fanuc: "nc", sinumerik: "mpf", grbl: "gcode" };

  function fmtTime(s) {
    if (s === null || s === undefined) return "–";
    return s >= 60 ? `${Math.floor(s / 60)} min ${(s % 60).toFixed(1)} s` : `${s.toFixed(2)} s`;
  }

  function showOutcome(m, o) {
    const r = m.report;
    const v = r.verification;
    const verdict = $("verdict");
    if (r.problems.length === 0) {
      verdict.className = "ok";
      verdict.textContent =
        `Verified: no gouge, nothing left to cut (min clearance ${v.min_clearance_mm.toFixed(4)} mm, ` +
        `needs ${v.required_clearance_mm.toFixed(4)}; uncut ${v.uncut_area_mm2.toFixed(3)} mm²). ` +
        `${r.strategy}: ${fmtTime(r.cycle_time_s)} on ${o.machine || "hsm"}, path ${r.path_length_mm.toFixed(0)} mm.`;
    } else {
      verdict.className = "bad";
      verdict.textContent = `Verification found problems: ${r.problems.join("; ")}`;
    }
    const rows = r.auto
      ? r.auto
      : [{ strategy: r.strategy, cycle_time_s: r.cycle_time_s, path_length_mm: r.path_length_mm,
           verified: r.problems.length === 0, why_not: r.problems[0] || null, chosen: true }];
    $("times").tBodies[0].replaceChildren(
      ...rows.map((e) => {
        const tr = document.createElement("tr");
        if (e.chosen) tr.className = "chosen";
        const cells = [
          e.strategy + (e.chosen && r.auto ? " (written)" : ""),
          fmtTime(e.cycle_time_s),
          e.path_length_mm === null ? "–" : `${e.path_length_mm.toFixed(0)} mm`,
          e.verified ? "verified" : e.why_not || "not verified",
        ];
        tr.replaceChildren(...cells.map((t) => Object.assign(document.createElement("td"), { textContent: t })));
        return tr;
      }),
    );
    if (downloadUrl) URL.revokeObjectURL(downloadUrl);
    downloadUrl = URL.createObjectURL(new Blob([m.gcode], { type: "text/plain" }));
    const a = $("download");
    const base = drawing.name.replace(/^sample:/, "").replace(/\.[^.]*$/, "") || "pocket";
    a.href = downloadUrl;
    a.download = `${base}.${extension[o.dialect || "linuxcnc"] || "nc"}`;
    a.textContent = `Download the program (${a.download}, ${m.gcode.length.toLocaleString("en")} bytes)`;
    $("timing").textContent = `planned in ${(m.planMs / 1000).toFixed(2)} s, report drawn in ${(m.drawMs / 1000).toFixed(2)} s`;
    $("preview").innerHTML = m.preview;
    $("report").srcdoc = m.html;
    $("outcome").hidden = false;
  }

  // Plans the current drawing with the form's options (and `extra` flags over them);
  // resolves with the worker's answer, and the flags used, once it is shown.
  async function plan(extra = {}) {
    const o = { ...options(), ...extra };
    $("command").textContent = command(drawing.name, o);
    clearResults();
    $("plan").disabled = true;
    $("progress").hidden = false;
    document.body.dataset.state = "planning";
    const t0 = performance.now();
    const tick = setInterval(() => {
      $("elapsed").textContent = `${((performance.now() - t0) / 1000).toFixed(0)} s`;
    }, 500);
    $("stage").textContent = "starting the engine";
    $("elapsed").textContent = "";
    const m = await ask({ kind: "plan", name: drawing.name, bytes: drawing.bytes, options: o }, (s) => {
      $("stage").textContent = s;
    });
    clearInterval(tick);
    $("progress").hidden = true;
    $("plan").disabled = false;
    if (m.ok) {
      showFound(m.pockets, m.notes);
      showOutcome(m, o);
    } else {
      showError(m.message);
    }
    document.body.dataset.state = m.ok ? "planned" : "refused";
    return { ...m, options: o };
  }

  // A drawing chosen: its pockets listed at once (or the reader's refusal shown).
  async function choose(name, bytes) {
    drawing = { name, bytes };
    $("drawing-name").textContent = name;
    clearResults();
    const m = await ask({ kind: "list", name, bytes, options: options() });
    if (m.ok) {
      showFound(m.pockets, []);
    } else {
      showFound([], []);
      showError(m.message);
    }
    return m;
  }

  async function chooseFile(file) {
    if (!file) return;
    await choose(file.name, new Uint8Array(await file.arrayBuffer()));
  }

  $("file").addEventListener("change", (e) => chooseFile(e.target.files[0]));
  $("sample").addEventListener("change", (e) => choose(e.target.value, null));
  const drop = $("drop");
  drop.addEventListener("dragover", (e) => {
    e.preventDefault();
    drop.classList.add("over");
  });
  drop.addEventListener("dragleave", () => drop.classList.remove("over"));
  drop.addEventListener("drop", (e) => {
    e.preventDefault();
    drop.classList.remove("over");
    chooseFile(e.dataTransfer.files[0]);
  });
  $("job").addEventListener("submit", (e) => {
    e.preventDefault();
    plan();
  });

  // Runs the test cases at `url` through the page (see the header).
  async function selftest(url) {
    const base = new URL(".", new URL(url, location.href));
    const post = (path, body) => fetch(new URL(path, base), { method: "POST", body });
    const cases = await (await fetch(url)).json();
    for (const c of cases) {
      const bytes = c.url ? new Uint8Array(await (await fetch(c.url)).arrayBuffer()) : null;
      drawing = { name: c.name, bytes };
      $("drawing-name").textContent = c.name;
      setOptions(c.options);
      const m = await plan(c.options);
      const shown = {
        ok: m.ok,
        options: m.options,
        planMs: m.planMs ?? null,
        error: $("error").hidden ? null : $("error").textContent,
      };
      if (m.ok) {
        shown.verdict = $("verdict").textContent;
        shown.download = $("download").download;
        shown.rows = $("times").tBodies[0].rows.length;
        await post(`result/${c.id}`, await (await fetch($("download").href)).blob());
      }
      await post(`result/${c.id}.json`, JSON.stringify(shown));
    }
    await post("done", "{}");
  }

  async function start() {
    const meta = await ask({ kind: "meta" });
    if (meta.ok) {
      $("version").textContent = meta.version;
      $("machine").replaceChildren(
        ...meta.machines.map((n) => Object.assign(document.createElement("option"), { value: n, textContent: n })),
      );
    } else {
      showError(meta.message);
    }
    $("plan").disabled = false;
    document.body.dataset.state = "ready";
    if (params.get("selftest")) {
      await selftest(params.get("selftest"));
      return;
    }
    const asked = params.get("plan");
    const o = {};
    for (const [k, v] of params) if (!["plan", "hold", "release"].includes(k)) o[k] = v;
    setOptions(o);
    if (asked) {
      $("sample").value = asked;
      await choose(asked, null);
      await plan(o);
    } else {
      await choose(drawing.name, null);
    }
    if (params.get("release")) await fetch(params.get("release"), { method: "POST", body: "{}" });
  }

  if (params.get("hold")) {
    // An image in the document holds the load event (and so a headless screenshot) until
    // the server answers it, which it does once the result is drawn and `release` posted.
    document.body.append(Object.assign(document.createElement("img"), { src: params.get("hold"), alt: "", hidden: true }));
  }
  start();
}
