// The teaching console's page: every action is a call to the JSON API (docs/console.md).
// Every change carries the table's version (a stale tab gets 409 and reloads the table);
// buttons are disabled while a request is in flight, so a double click teaches once.
"use strict";
const $ = (id) => document.getElementById(id);
let scene = null;          // the last GET/POST /api/scene answer
let drag = null;           // {index, moved} while an object is dragged
let busy = false;          // a request is in flight
// Timing of the last lesson, for the browser test: answer received -> new image shown (ms).
window.aileenTiming = { answerAt: null, sceneAt: null, sceneMs: null };

// `stale`: a 409 for a table another tab changed (it carries the version); a 409 from Save is
// another program's write to the memory file, said as the server says it
class ApiError extends Error {
  constructor(status, message, stale) { super(message); this.status = status; this.stale = stale; }
}

async function api(method, path, body) {
  const opts = { method, headers: {} };
  if (body !== undefined) { opts.body = JSON.stringify(body); opts.headers["Content-Type"] = "application/json"; }
  const r = await fetch(path, opts);
  const data = await r.json().catch(() => ({ error: `the server answered HTTP ${r.status}` }));
  if (!r.ok) throw new ApiError(r.status, data.error || `the server answered HTTP ${r.status}`,
                                r.status === 409 && data.version !== undefined);
  return data;
}

function versioned(body) { return Object.assign({ version: scene ? scene.version : undefined }, body); }

function status(text) { $("status").textContent = text || ""; }

function showError(where, message) {
  const box = $(where);
  box.textContent = message || ""; box.hidden = !message;
}

function clearErrors() { for (const id of ["scene-error", "lesson-error", "memory-error"]) showError(id, ""); }

// Run one request with every button disabled; a 409 reloads the table and says why.
async function exclusive(errorBox, work) {
  if (busy) return;
  busy = true; document.body.classList.add("busy");
  const buttons = [...document.querySelectorAll("button")];
  for (const b of buttons) b.disabled = true;
  clearErrors(); status("");
  try {
    await work();
  } catch (e) {
    if (e.stale) {
      await reloadAll();
      showError(errorBox, "The table changed in another tab or window; it is shown here as it is now. Nothing was done: look, then try again.");
    } else {
      showError(errorBox, e.message);
    }
    if (errorBox === "lesson-error") { $("answer").className = "stale"; }
  } finally {
    busy = false; document.body.classList.remove("busy");
    for (const b of buttons) b.disabled = false;
    $("undo-lesson").disabled = !(scene && scene.undo);
    if ($("status").textContent === "thinking…") status("");
  }
}

let fresh = 0;  // bumped when the image must be fetched again before the scene's version is known
function imageUrl(frame) {
  const ov = $("overlay").checked ? 1 : 0;
  const v = `${scene ? scene.version : 0}.${fresh}`;
  return `/api/scene.png?overlay=${ov}&v=${v}` + (frame === undefined ? "" : `&frame=${frame}`);
}

function idOrder(a, b) {
  const n = (o) => (o.seen_id ? parseInt(o.seen_id.slice(1), 10) : 1e9);
  return n(a) - n(b) || a.index - b.index;
}

function showScene(data, imageShown) {
  scene = data;
  if (!imageShown) $("scene").src = imageUrl();
  const ul = $("objects"); ul.innerHTML = "";
  for (const o of [...data.objects].sort(idOrder)) {
    const li = document.createElement("li");
    const id = document.createElement("b"); id.className = "agent-id";
    id.textContent = o.seen_id || "?";
    id.title = o.seen_id ? "the agent's id for this object" : "the agent does not see this object";
    li.append(id, ` ${o.name}${o.distractor ? " (distractor)" : ""} at (${o.x.toFixed(2)}, ${o.y.toFixed(2)})`);
    const b = document.createElement("button"); b.textContent = "remove"; b.dataset.index = o.index;
    b.onclick = () => edit({ op: "remove", index: o.index });
    li.appendChild(b); ul.appendChild(li);
  }
  const rels = (data.relations || []).map((r) => `${r.from} ${r.word} ${r.to}`);
  $("highlight").textContent = data.highlight.length
    ? `grounded (highlighted): ${data.highlight.join(" ")}${rels.length ? `; drawn: ${rels.join(", ")}` : ""}` : "";
  $("playback").hidden = !data.frames;
  $("frame-no").textContent = data.frames ? `${data.frames} frames` : "";
  $("undo-lesson").disabled = busy || !data.undo;
}

async function reloadAll() {
  showScene(await api("GET", "/api/scene"));
  await showTranscript();
  if (!$("memory").hidden) await showMemory();
}

function edit(body) {
  return exclusive("scene-error", async () => { showScene(await api("POST", "/api/scene", versioned(body))); });
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
  ev.preventDefault();
  if (busy) return;
  const [u, v] = pixelAt(ev);
  drag = { index: objectAt(u, v), moved: false };
});
$("scene").addEventListener("mousemove", () => { if (drag) drag.moved = true; });
$("scene").addEventListener("mouseup", (ev) => {
  const [u, v] = pixelAt(ev), d = drag; drag = null;
  if (!d || busy) return;
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

// What an answer means for the person teaching: {kind, head, lines}.
// kind: learned / success / failure / neutral (the box's colour).
function outcome(r) {
  const learned = [...new Set((r.created || []).concat(r.stored || []))];
  const lines = [];
  const refs = Object.entries(r.referents || {}).map(([k, v]) => `${k} = ${v.join(" ") || "(not found)"}`);
  if (refs.length) lines.push(`grounded: ${refs.join(", ")}`);
  const made = [];
  if (r.created.length) made.push(`created ${r.created.join(", ")}`);
  if (r.stored.length) made.push(`stored ${r.stored.join(", ")}`);
  if (made.length) lines.push(made.join("; "));
  if (r.signal === "inform") {
    if (learned.length) {
      if (r.reason) lines.push(`it did not understand the sentence yet (${r.reason}), so it learned from it`);
      return { kind: "learned", word: "learned", head: learned.join(", "), lines };
    }
    if (r.result === "success") return { kind: "success", word: "success", head: "understood: nothing new to learn", lines };
    return { kind: "failure", word: "failure", head: `did not learn anything: ${r.reason || "no reason given"}`, lines };
  }
  if (r.signal === "verify") {
    const says = r.result === "success" ? "the agent says it is true" : `the agent says it is not true${r.reason ? ` (${r.reason})` : ""}`;
    if (r.expected) lines.push(`the trainer expected ${r.expected}: ${r.correct ? "right" : "WRONG"}`);
    else lines.push("not graded: the trainer cannot tell");
    const grade = r.correct === true ? "right" : r.correct === false ? "WRONG" : "not graded";
    return { kind: r.correct === true ? "success" : r.correct === false ? "failure" : "neutral", word: r.result, head: says, grade, lines };
  }
  if (r.signal === "react") {
    lines.push(`plan: ${(r.steps || []).join(", ") || "nothing"} (${r.projections} projections)`);
    const goal = r.goal_holds === true ? "the goal was reached" : r.goal_holds === false ? "the goal was NOT reached" : "the trainer cannot tell whether the goal was reached";
    return { kind: r.goal_holds === true ? "success" : r.goal_holds === false ? "failure" : "neutral", word: r.result, head: `${r.result === "success" ? "acted" : `could not act${r.reason ? `: ${r.reason}` : ""}`}; ${goal}`, lines };
  }
  if (r.signal === "generate") {
    const grade = r.correct === true ? "true of the table" : r.correct === false ? "NOT true of the table" : "not graded (the trainer cannot read this sentence)";
    if (r.reason) lines.push(r.reason);
    return { kind: r.correct === true ? "success" : r.correct === false ? "failure" : "neutral", word: r.result, head: `said "${r.said || ""}": ${grade}`, lines };
  }
  if (r.signal === "wrong" || r.signal === "right" || r.signal === "confirm") {
    const what = { wrong: "learned from the correction", right: "kept the answer", confirm: "kept its plan as an example" }[r.signal];
    return { kind: learned.length ? "learned" : "neutral", word: learned.length ? "learned" : r.result, head: learned.length ? `${what}: ${learned.join(", ")}` : `${what} (nothing changed)`, lines };
  }
  return { kind: "neutral", word: r.result, head: r.result, lines };
}

function describeAnswer(r) {
  const o = outcome(r), box = $("answer");
  box.className = o.kind; box.innerHTML = "";
  const head = document.createElement("div"); head.className = "headline";
  const said = document.createElement("span"); said.className = "said";
  said.textContent = `${r.signal === "generate" ? "describe" : r.signal}${r.content ? ` "${r.content}"` : ""}`;
  const res = document.createElement("span"); res.id = "result"; res.className = `result-${o.kind}`;
  res.textContent = o.word;
  const text = document.createElement("span"); text.id = "verdict"; text.textContent = o.head;
  head.append(said, " ", res, ": ", text);
  box.appendChild(head);
  for (const l of o.lines) { const d = document.createElement("div"); d.textContent = l; box.appendChild(d); }
}

async function showTranscript() {
  const recs = (await api("GET", "/api/lessons")).records, ol = $("transcript");
  ol.innerHTML = "";
  for (const r of recs) {
    const o = outcome(r), li = document.createElement("li");
    li.className = o.kind;
    li.textContent = `${r.signal === "generate" ? "describe" : r.signal}${r.content ? ` "${r.content}"` : ""} → ${o.word}: ${o.head}${o.grade ? ` (${o.grade})` : ""}`;
    ol.appendChild(li);
  }
}

const TAKES_CONTENT = new Set(["inform", "verify", "react"]);

$("lesson-form").addEventListener("submit", (ev) => {
  ev.preventDefault();
  exclusive("lesson-error", async () => {
    status("thinking…");
    $("answer").className = "pending";
    const signal = $("signal").value;  // describe and the verdicts take no sentence: the text box stays for the next one
    const r = await api("POST", "/api/lesson", versioned({ signal, content: TAKES_CONTENT.has(signal) ? $("content").value : "" }));
    const t0 = performance.now();
    window.aileenTiming = { answerAt: t0, sceneAt: null, sceneMs: null };
    describeAnswer(r);
    if (r.autosave_error) status(r.autosave_error);  // the lesson stands; its save went elsewhere
    const img = $("scene");
    img.onload = () => {
      img.onload = null;
      const t1 = performance.now();
      window.aileenTiming = { answerAt: t0, sceneAt: t1, sceneMs: t1 - t0 };
    };
    fresh += 1;
    img.src = imageUrl();  // the lesson's last view is ready now: fetch it while the scene JSON comes
    showScene(await api("GET", "/api/scene"), true);
    await showTranscript();
    if (!$("memory").hidden) await showMemory();
  });
});

$("undo-lesson").onclick = () => exclusive("lesson-error", async () => {
  const u = await api("POST", "/api/lesson/undo", versioned({}));
  showScene(u.scene);
  const box = $("answer"); box.className = "neutral"; box.innerHTML = "";
  const d = document.createElement("div"); d.className = "headline"; d.id = "undone";
  const what = u.undone.signal === "forget" ? `forget ${u.undone.content}` : `${u.undone.signal}${u.undone.content ? ` "${u.undone.content}"` : ""}`;
  d.textContent = `undid ${what}: the memory, the table and the transcript are as they were before it`;
  box.appendChild(d);
  if (u.autosave_error) status(u.autosave_error);
  await showTranscript();
  if (!$("memory").hidden) await showMemory();
});

function cell(row, text, cls) {
  const td = document.createElement("td"); td.textContent = text; if (cls) td.className = cls; row.appendChild(td); return td;
}

function factTable(facts, threshold) {
  const t = document.createElement("table"); t.className = "facts";
  for (const [fact, p] of Object.entries(facts).sort((a, b) => b[1] - a[1] || a[0].localeCompare(b[0]))) {
    const tr = document.createElement("tr"); if (p < threshold) tr.className = "weak";
    cell(tr, fact, "fact");
    const bar = cell(tr, "", "bar"), fill = document.createElement("div");
    fill.style.width = `${Math.round(p * 100)}%`; bar.appendChild(fill);
    cell(tr, p.toFixed(2), "p");
    t.appendChild(tr);
  }
  return t;
}

function qualityTable(c) {
  const q = c.concept_quality || {}, t = document.createElement("table"); t.className = "quality";
  const rows = [["examples seen", q.examples_seen], ["generalizations", q.generalizations],
    ["examples kept apart", q.examples_apart], ["facts that count", q.significant_facts],
    ["near misses", q.near_misses], ["separation from its kind", q.separation],
    ["confused with", (q.confused_with || []).join(", ") || "none"]];
  if (c.quality) rows.push(["verify this session", `${c.quality.verify_right}/${c.quality.verify_graded} right`]);
  for (const [k, v] of rows) {
    if (v === undefined) continue;
    const tr = document.createElement("tr"); cell(tr, k, "key"); cell(tr, String(v)); t.appendChild(tr);
  }
  return t;
}

async function showMemory() {
  const m = await api("GET", "/api/memory"), div = $("memory");
  div.innerHTML = ""; div.hidden = false;
  const t = m.thresholds;
  const p = document.createElement("p");
  p.textContent = `thresholds: assimilation ${t.assimilation}, probability ${t.probability} (facts below it are grey: they do not count), match ${t.match}`;
  div.appendChild(p);
  const names = Object.keys(m.concepts);
  if (!names.length) { div.append("(no concepts yet)"); return; }
  for (const sym of names) {
    const c = m.concepts[sym], d = document.createElement("details"); d.open = true;
    d.className = "concept"; d.dataset.symbol = sym;
    const s = document.createElement("summary");
    const name = document.createElement("b"); name.textContent = `"${c.word || "?"}"`;
    const gs = c.generalizations.length, es = c.examples.length;
    s.append(name, ` ${sym} (${c.kind}): ${gs} generalization${gs === 1 ? "" : "s"}, ${es} example${es === 1 ? "" : "s"} kept apart`);
    if (c.quality) s.append(`; verify ${c.quality.verify_right}/${c.quality.verify_graded} right this session`);
    const forget = document.createElement("button"); forget.className = "forget"; forget.textContent = "forget";
    forget.title = `forget ${sym}: its generalizations, examples and word (undo last lesson takes it back)`;
    forget.onclick = (ev) => { ev.preventDefault(); forgetConcept(sym); };
    s.append(" ", forget);
    d.appendChild(s);
    const body = document.createElement("div"); body.className = "concept-body";
    const facts = document.createElement("div"), side = document.createElement("div");
    c.generalizations.forEach((g, i) => {
      const h = document.createElement("h4"); h.textContent = `generalization ${i + 1} (of ${g.examples} examples)`;
      facts.append(h, factTable(g.facts, t.probability));
    });
    c.examples.forEach((ex, i) => {
      const h = document.createElement("h4"); h.textContent = `example ${i + 1} (kept apart)`;
      facts.append(h, factTable(Object.fromEntries(ex.map((f) => [f, 1])), t.probability));
    });
    if ((c.near_misses || []).length) {
      const h = document.createElement("h4"); h.textContent = `${c.near_misses.length} near miss${c.near_misses.length === 1 ? "" : "es"}`;
      facts.appendChild(h);
    }
    const qh = document.createElement("h4"); qh.textContent = "quality";
    side.append(qh, qualityTable(c));
    body.append(facts, side); d.appendChild(body);
    const raw = document.createElement("details"); raw.className = "raw";
    const rs = document.createElement("summary"); rs.textContent = "as aileen memory show prints it";
    const pre = document.createElement("pre"); pre.textContent = c.text;
    raw.append(rs, pre); d.appendChild(raw);
    div.appendChild(d);
  }
}

function forgetConcept(sym) {
  return exclusive("memory-error", async () => {
    const f = await api("POST", "/api/forget", versioned({ concept: sym }));
    status(f.autosave_error || `forgot ${f.forgot}${f.word ? ` ("${f.word}")` : ""}; undo last lesson takes it back`);
    showScene(await api("GET", "/api/scene"));
    await showMemory();
  });
}

$("memory-open").onclick = () => exclusive("memory-error", showMemory);
$("save").onclick = () => exclusive("memory-error", async () => {
  status((await api("POST", "/api/save", {})).saved);
});
$("download").addEventListener("click", (ev) => {
  if (!$("transcript").children.length) { ev.preventDefault(); showError("lesson-error", "There are no lessons to download yet."); }
});

$("curves-open").onclick = () => exclusive("memory-error", async () => {
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
});

// The words the page offers come from the server's declarations (GET /api/words): the
// relations an object can be put in, and the channels an object description may name.
async function showWords() {
  const w = await api("GET", "/api/words");
  const sel = $("relation");
  for (const word of w.relations) {
    const opt = document.createElement("option"); opt.textContent = word; sel.appendChild(opt);
  }
  const said = w.channels.filter((c) => c.name !== "shape").reverse().map((c) => c.default ? `[${c.name}]` : c.name);
  $("object").title = `${said.join(" ")} shape: ` + w.channels.map((c) => `${c.name} one of ${c.values.join(", ")}`).join("; ");
}

showWords().then(reloadAll).then(() => { window.aileenReady = true; }).catch((e) => showError("scene-error", e.message));
