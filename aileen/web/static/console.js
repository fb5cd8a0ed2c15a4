// The teaching console's page: every action is a call to the JSON API (docs/console.md).
"use strict";
const $ = (id) => document.getElementById(id);
let scene = null;          // the last GET/POST /api/scene answer
let drag = null;           // {index, moved} while an object is dragged
// Timing of the last lesson, for the browser test: answer received -> new image shown (ms).
window.aileenTiming = { answerAt: null, sceneAt: null, sceneMs: null };

async function api(method, path, body) {
  const opts = { method, headers: {} };
  if (body !== undefined) { opts.body = JSON.stringify(body); opts.headers["Content-Type"] = "application/json"; }
  const r = await fetch(path, opts);
  const data = await r.json().catch(() => ({ error: `HTTP ${r.status}` }));
  if (!r.ok) throw new Error(data.error || `HTTP ${r.status}`);
  return data;
}

function status(text, isError) {
  const s = $("status"); s.textContent = text || ""; s.className = isError ? "error" : "";
}

let fresh = 0;  // bumped when the image must be fetched again before the scene's version is known
function imageUrl(frame) {
  const ov = $("overlay").checked ? 1 : 0;
  const v = `${scene ? scene.version : 0}.${fresh}`;
  return `/api/scene.png?overlay=${ov}&v=${v}` + (frame === undefined ? "" : `&frame=${frame}`);
}

function showScene(data, imageShown) {
  scene = data;
  if (!imageShown) $("scene").src = imageUrl();
  const ul = $("objects"); ul.innerHTML = "";
  for (const o of data.objects) {
    const li = document.createElement("li");
    li.textContent = `${o.index + 1}. ${o.name}${o.distractor ? " (distractor)" : ""} at (${o.x.toFixed(2)}, ${o.y.toFixed(2)})`;
    const b = document.createElement("button"); b.textContent = "remove"; b.dataset.index = o.index;
    b.onclick = () => edit({ op: "remove", index: o.index });
    li.appendChild(b); ul.appendChild(li);
  }
  $("highlight").textContent = data.highlight.length ? `grounded (highlighted): ${data.highlight.join(" ")}` : "";
  $("playback").hidden = !data.frames;
  $("frame-no").textContent = data.frames ? `${data.frames} frames` : "";
}

async function edit(body) {
  try { showScene(await api("POST", "/api/scene", body)); status(""); }
  catch (e) { status(e.message, true); }
}

function pixelAt(ev) {
  const img = $("scene"), r = img.getBoundingClientRect(), k = scene ? scene.scale : 2;
  return [(ev.clientX - r.left) / k, (ev.clientY - r.top) / k];
}

function objectAt(u, v) {
  if (!scene) return null;
  for (const o of scene.objects) {
    if (Math.abs(o.px[0] - u) <= o.half_px && Math.abs(o.px[1] - v) <= o.half_px) return o.index;
  }
  return null;
}

$("scene").addEventListener("mousedown", (ev) => {
  const [u, v] = pixelAt(ev), i = objectAt(u, v);
  drag = { index: i, moved: false };
  ev.preventDefault();
});
$("scene").addEventListener("mousemove", () => { if (drag) drag.moved = true; });
$("scene").addEventListener("mouseup", (ev) => {
  const [u, v] = pixelAt(ev), d = drag; drag = null;
  if (!d) return;
  if (d.index !== null && d.moved) edit({ op: "move", index: d.index, px: [u, v] });
  else if (d.index === null) edit(addBody({ px: [u, v] }));
});

function addBody(extra) {
  const body = { op: "add", object: $("object").value };
  return Object.assign(body, extra);
}

$("add").onclick = () => {
  const rel = $("relation").value;
  edit(rel ? addBody({ relation: rel, of: $("of").value }) : addBody({}));
};
$("shuffle").onclick = () => edit({ op: "shuffle", distractors: parseInt($("distractors").value || "0", 10) });
$("undo").onclick = () => edit({ op: "undo" });
$("clear").onclick = () => edit({ op: "clear" });
$("overlay").onchange = () => { $("scene").src = imageUrl(); };

$("play").onclick = async () => {
  const n = scene ? scene.frames : 0;
  for (let k = 0; k < n; k++) {
    $("scene").src = imageUrl(k); $("frame-no").textContent = `frame ${k + 1} of ${n}`;
    await new Promise((ok) => setTimeout(ok, 600));
  }
  $("scene").src = imageUrl(); $("frame-no").textContent = `${n} frames`;
};

function describeAnswer(r) {
  const box = $("answer"); box.className = r.result; box.innerHTML = "";
  const head = document.createElement("div");
  const res = document.createElement("span"); res.className = `result-${r.result}`; res.id = "result";
  res.textContent = r.result; head.append(`${r.signal} "${r.content}": `, res);
  if (r.reason) head.append(`: ${r.reason}`);
  box.appendChild(head);
  const lines = [];
  const refs = Object.entries(r.referents || {}).map(([k, v]) => `${k} = ${v.join(" ") || "-"}`);
  if (refs.length) lines.push(`grounded: ${refs.join(", ")}`);
  if (r.created.length || r.stored.length) lines.push(`learned: created ${r.created.join(", ") || "-"}; stored ${r.stored.join(", ") || "-"}`);
  if (r.signal === "generate") lines.push(`said: "${r.said || ""}"${r.correct === null || r.correct === undefined ? "" : (r.correct ? " (true of the table)" : " (NOT true of the table)")}`);
  if (r.signal === "react") lines.push(`plan: ${(r.steps || []).join(", ") || "nothing"} (${r.projections} projections); goal ${r.goal_holds ? "reached" : "not reached"}`);
  if (r.expected) lines.push(`trainer expected ${r.expected}: ${r.correct ? "right" : "WRONG"}`);
  for (const l of lines) { const d = document.createElement("div"); d.textContent = l; box.appendChild(d); }
  const li = document.createElement("li");
  const learned = r.created.length || r.stored.length ? `; learned ${[...new Set(r.created.concat(r.stored))].join(", ")}` : "";
  li.textContent = `${r.signal} "${r.content}" → ${r.result}${r.correct === null || r.correct === undefined ? "" : (r.correct ? " (right)" : " (WRONG)")}${learned}`;
  $("transcript").appendChild(li);
}

$("lesson-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  status("thinking…");
  try {
    const r = await api("POST", "/api/lesson", { signal: $("signal").value, content: $("content").value });
    const t0 = performance.now();
    window.aileenTiming = { answerAt: t0, sceneAt: null, sceneMs: null };
    describeAnswer(r);
    const img = $("scene");
    img.onload = () => {
      img.onload = null;
      const t1 = performance.now();
      window.aileenTiming = { answerAt: t0, sceneAt: t1, sceneMs: t1 - t0 };
    };
    fresh += 1;
    img.src = imageUrl();  // the lesson's last view is ready now: fetch it while the scene JSON comes
    showScene(await api("GET", "/api/scene"), true);
    status("");
    if (!$("memory").hidden) showMemory();
  } catch (e) { status(e.message, true); }
});

async function showMemory() {
  const m = await api("GET", "/api/memory"), div = $("memory");
  div.innerHTML = ""; div.hidden = false;
  const t = m.thresholds;
  const p = document.createElement("p");
  p.textContent = `thresholds: assimilation ${t.assimilation}, probability ${t.probability}, match ${t.match}`;
  div.appendChild(p);
  const names = Object.keys(m.concepts);
  if (!names.length) { div.append("(no concepts yet)"); return; }
  for (const sym of names) {
    const c = m.concepts[sym], d = document.createElement("details"); d.open = true;
    d.className = "concept"; d.dataset.symbol = sym;
    const s = document.createElement("summary");
    let q = "";
    if (c.quality) q = `; verify ${c.quality.verify_right}/${c.quality.verify_graded} right this session`;
    s.textContent = `${sym} "${c.word || "?"}" (${c.kind}): ${c.generalizations.length} generalizations, ${c.examples.length} examples${q}`;
    const pre = document.createElement("pre"); pre.textContent = c.text;
    d.append(s, pre); div.appendChild(d);
  }
}

$("memory-open").onclick = () => showMemory().catch((e) => status(e.message, true));
$("save").onclick = async () => {
  try { status((await api("POST", "/api/save", {})).saved); } catch (e) { status(e.message, true); }
};
$("download").addEventListener("click", (ev) => {
  if (!$("transcript").children.length) { ev.preventDefault(); status("no lessons given yet", true); }
});

$("curves-open").onclick = async () => {
  try {
    const x = await api("GET", "/api/experiment"), div = $("curves");
    div.innerHTML = ""; div.hidden = false;
    if (x.note) div.append(x.note);
    for (const f of x.files) {
      const h = document.createElement("h3"); h.textContent = f.name; div.appendChild(h);
      if (f.name.endsWith(".png")) {
        const img = document.createElement("img"); img.src = `/api/experiment/${f.index}`; img.alt = f.name; div.appendChild(img);
      } else {
        const pre = document.createElement("pre"); pre.textContent = await (await fetch(`/api/experiment/${f.index}`)).text();
        div.appendChild(pre);
      }
    }
    if (x.summary) { const pre = document.createElement("pre"); pre.textContent = JSON.stringify(x.summary, null, 2); div.appendChild(pre); }
  } catch (e) { status(e.message, true); }
};

api("GET", "/api/scene").then(showScene).catch((e) => status(e.message, true));
