// The animated page of `workcell ... --html`: the robots moving over the still drawing of
// the cell, the controls, the Gantt chart's cursor and what each robot is doing.
"use strict";
(function () {
  const page = JSON.parse(document.getElementById("model").textContent);
  const m = page.model;
  const F = page.frame;
  const A = page.axis;
  const NS = "http://www.w3.org/2000/svg";
  const t0 = page.t0;
  const t1 = page.t1;
  const slider = document.getElementById("slider");
  const play = document.getElementById("play");
  const speed = document.getElementById("speed");
  const clock = document.getElementById("clock");
  const info = document.getElementById("info");
  const cursor = document.getElementById("cursor");
  const robotsLayer = document.getElementById("robots");
  const overlay = document.getElementById("overlay");
  // The contact is shown this close to its time (a fraction of the horizon).
  const CONTACT_WINDOW = 0.01 * (t1 - t0);

  // The samples about t: [p, q, u], t at the fraction u of the way from p to q; the first
  // sample twice before the samples, the last twice after them (u = 0).
  function segment(samples, t) {
    let lo = 0;
    let hi = samples.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (samples[mid][0] <= t) lo = mid + 1;
      else hi = mid;
    }
    if (lo === 0) return [samples[0], samples[0], 0];
    if (lo === samples.length) return [samples[lo - 1], samples[lo - 1], 0];
    const p = samples[lo - 1];
    const q = samples[lo];
    return [p, q, (t - p[0]) / (q[0] - p[0])];
  }

  // The pose at t exactly as the checker interpolates (src/motion/trajectory.rs): linear in
  // x, y and θ between samples, by the fraction of the time step; the first pose before the
  // samples and the last after them.
  function poseAt(samples, t) {
    const [p, q, u] = segment(samples, t);
    return [p[1] + (q[1] - p[1]) * u, p[2] + (q[2] - p[2]) * u, p[3] + (q[3] - p[3]) * u];
  }

  // A link's frame at t as the checker places it (src/motion/arm.rs): each joint linear
  // between samples, then forward kinematics from the base (contract section 6).
  function linkPose(arm, t) {
    const [p, q, u] = segment(arm.joints, t);
    const angle = function (j) {
      return u === 0 ? p[j + 1] : p[j + 1] + (q[j + 1] - p[j + 1]) * u;
    };
    let x = arm.base[0];
    let y = arm.base[1];
    let th = arm.base[2] + angle(0);
    for (let k = 1; k <= arm.link; k++) {
      x += arm.lengths[k - 1] * Math.cos(th);
      y += arm.lengths[k - 1] * Math.sin(th);
      th += angle(k);
    }
    return [x, y, th];
  }

  function poseOf(robot, t) {
    return robot.arm ? linkPose(robot.arm, t) : poseAt(robot.samples, t);
  }

  function px(x, y) {
    return [F.ox + x * F.scale, F.oy - y * F.scale];
  }

  function el(name, attrs) {
    const e = document.createElementNS(NS, name);
    for (const k in attrs) e.setAttribute(k, attrs[k]);
    return e;
  }

  function activity(robot, t) {
    for (const b of robot.bars) {
      if (b.start <= t && t < b.end) return b;
    }
    return null;
  }

  function describe(robot, t) {
    const b = activity(robot, t);
    if (b) return b.label + " [" + b.start.toFixed(3) + "-" + b.end.toFixed(3) + "]";
    return robot.home ? "back home" : "at rest";
  }

  let selected = null;
  function showInfo(r) {
    if (r === null) return;
    const robot = m.robots[r];
    info.textContent = robot.name + " at t = " + t.toFixed(3) + ": " + describe(robot, t);
    info.style.borderColor = robot.colour;
  }

  // A robot is a group: its body (one polygon, or one per part for a body given by parts)
  // and, for a body given by an outline, the seams of its convex parts, shown on hover.
  const shapes = m.robots.map(function (robot, r) {
    const g = el("g", { id: "robot-" + r, "data-name": robot.name });
    const body = robot.parts && !robot.outlined ? robot.parts : [robot.shape];
    const polys = body.map(function (local) {
      const p = el("polygon", {
        fill: robot.colour,
        "fill-opacity": 0.55,
        stroke: robot.colour,
        "stroke-width": 1.5,
      });
      g.appendChild(p);
      return { local: local, el: p };
    });
    // An arm: its base a square, each joint past the base a dot at its link's origin.
    let joint = null;
    if (robot.arm && robot.arm.link === 0) {
      const b = px(robot.arm.base[0], robot.arm.base[1]);
      g.appendChild(el("rect", { class: "base", x: b[0] - 5, y: b[1] - 5, width: 10, height: 10, fill: robot.colour }));
    } else if (robot.arm) {
      joint = el("circle", { class: "joint", r: 3.5, fill: robot.colour, stroke: "#fff", "stroke-width": 1 });
    }
    const seams = (robot.outlined ? robot.parts : []).map(function (local) {
      const p = el("polygon", { fill: "none", stroke: "#000", "stroke-opacity": 0.35, "stroke-width": 0.5 });
      p.setAttribute("visibility", "hidden");
      g.appendChild(p);
      return { local: local, el: p };
    });
    const seen = function (on) {
      seams.forEach(function (s) {
        s.el.setAttribute("visibility", on ? "visible" : "hidden");
      });
    };
    g.style.cursor = "pointer";
    g.addEventListener("mouseenter", function () {
      seen(true);
      showInfo(r);
    });
    g.addEventListener("mouseleave", function () {
      seen(false);
      showInfo(selected);
    });
    g.addEventListener("click", function () {
      selected = r;
      showInfo(r);
    });
    if (joint) g.appendChild(joint);
    robotsLayer.appendChild(g);
    return { polys: polys, seams: seams, joint: joint };
  });

  // A row per robot: an arm's links share its first link's.
  const statusCells = m.robots.map(function (robot) {
    if (robot.arm && robot.arm.link > 0) return null;
    const row = document.createElement("tr");
    const name = document.createElement("td");
    name.textContent = robot.name;
    name.style.color = robot.colour;
    const what = document.createElement("td");
    row.appendChild(name);
    row.appendChild(what);
    document.getElementById("status").appendChild(row);
    return what;
  });

  // A ring on a collision's point, with its round number.
  function ring(mark, id) {
    const c = px(mark.point[0], mark.point[1]);
    const g = el("g", { id: id, visibility: "hidden" });
    g.appendChild(el("circle", { cx: c[0], cy: c[1], r: 12, fill: "none", stroke: "#d50000", "stroke-width": 3 }));
    const label = el("text", { x: c[0] + 15, y: c[1] - 12, fill: "#d50000", "font-size": 13, "font-weight": "bold" });
    label.textContent = mark.round ? "round " + mark.round : "first contact";
    g.appendChild(label);
    overlay.appendChild(g);
    return g;
  }
  const contactRing = m.contact ? ring(m.contact, "contact") : null;
  let shownRound = null;
  const roundRings = m.rounds.map(function (mark, k) {
    return ring(mark, "round-" + (k + 1));
  });

  const marks = document.getElementById("marks");
  if (m.rounds.length > 0) {
    const caption = document.createElement("p");
    caption.textContent = "The collision of each feedback round, in the schedule that round checked (click to see where):";
    marks.appendChild(caption);
  }
  function jump(label, time, onClick) {
    const b = document.createElement("button");
    b.type = "button";
    b.textContent = label;
    b.addEventListener("click", function () {
      pause();
      setTime(time);
      onClick();
    });
    marks.appendChild(b);
  }
  if (m.contact) {
    const c = m.contact;
    jump("first contact: " + c.bodies[0] + " and " + c.bodies[1] + " at t = " + c.time.toFixed(3), c.time, function () {});
  }
  m.rounds.forEach(function (mark, k) {
    const text = "round " + mark.round + ": " + mark.bodies[0] + " and " + mark.bodies[1] + " at t = " + mark.time.toFixed(3);
    jump(text, mark.time, function () {
      if (shownRound !== null) roundRings[shownRound].setAttribute("visibility", "hidden");
      shownRound = k;
      roundRings[k].setAttribute("visibility", "visible");
    });
  });

  // The slider's track: the certified-free prefix (check) and the contact.
  const track = document.getElementById("track");
  const frac = function (t) {
    return (100 * (t - t0)) / (t1 - t0 || 1);
  };
  if (m.safe_until !== null) {
    const f = frac(m.safe_until);
    track.style.background = "linear-gradient(to right, #66bb6a 0%, #66bb6a " + f + "%, #ffcc80 " + f + "%, #ffcc80 100%)";
    track.title = "certified collision-free until t = " + m.safe_until;
  }
  if (m.contact) {
    const tick = document.createElement("div");
    tick.className = "tick";
    tick.style.left = frac(m.contact.time) + "%";
    track.appendChild(tick);
  }

  let t = t0;
  function draw() {
    m.robots.forEach(function (robot, r) {
      const p = poseOf(robot, t);
      const c = Math.cos(p[2]);
      const s = Math.sin(p[2]);
      const place = function (local) {
        return local
          .map(function (v) {
            const q = px(p[0] + c * v[0] - s * v[1], p[1] + s * v[0] + c * v[1]);
            return q[0].toFixed(3) + "," + q[1].toFixed(3);
          })
          .join(" ");
      };
      const hit = m.contact && Math.abs(t - m.contact.time) <= CONTACT_WINDOW && m.contact.bodies.indexOf(robot.name) >= 0;
      shapes[r].polys.forEach(function (poly) {
        poly.el.setAttribute("points", place(poly.local));
        poly.el.setAttribute("stroke", hit ? "#d50000" : robot.colour);
        poly.el.setAttribute("stroke-width", hit ? 4 : 1.5);
      });
      shapes[r].seams.forEach(function (seam) {
        seam.el.setAttribute("points", place(seam.local));
      });
      if (shapes[r].joint) {
        const j = px(p[0], p[1]);
        shapes[r].joint.setAttribute("cx", j[0].toFixed(3));
        shapes[r].joint.setAttribute("cy", j[1].toFixed(3));
      }
      const what = describe(robot, t);
      if (statusCells[r] && statusCells[r].textContent !== what) statusCells[r].textContent = what;
    });
    if (contactRing) {
      const near = Math.abs(t - m.contact.time) <= CONTACT_WINDOW;
      contactRing.setAttribute("visibility", near ? "visible" : "hidden");
    }
    if (cursor) {
      const x = A.left + (t - A.t0) * A.scale;
      cursor.setAttribute("x1", x);
      cursor.setAttribute("x2", x);
    }
    clock.textContent = "t = " + t.toFixed(3) + " / " + t1.toFixed(3);
    showInfo(selected);
  }

  function setTime(v) {
    t = Math.min(Math.max(v, t0), t1);
    slider.value = t;
    draw();
  }

  let playing = false;
  let last = null;
  function pause() {
    playing = false;
    play.textContent = "Play";
  }
  play.addEventListener("click", function () {
    if (playing) {
      pause();
      return;
    }
    if (t >= t1) setTime(t0);
    playing = true;
    last = null;
    play.textContent = "Pause";
  });
  slider.addEventListener("input", function () {
    setTime(parseFloat(slider.value));
  });
  function frame(now) {
    if (playing) {
      if (last !== null) {
        const next = t + ((now - last) / 1000) * parseFloat(speed.value);
        setTime(next);
        if (next >= t1) pause();
      }
      last = now;
    }
    requestAnimationFrame(frame);
  }
  // The speed whose run takes about 20 s, among those offered.
  let best = speed.options[0];
  for (const o of speed.options) {
    if (Math.abs(Math.log(((t1 - t0) / 20) / o.value)) < Math.abs(Math.log(((t1 - t0) / 20) / best.value))) best = o;
  }
  speed.value = best.value;
  // A tall Gantt chart (many robots) shrinks to the height of its column less the rounds'
  // buttons: the whole chart and the buttons stay in the window, never below the fold (what
  // the robots are doing may scroll, under them).
  const side = document.getElementById("side");
  const ganttSvg = document.querySelector("#gantt svg");
  function fitGantt() {
    const room = side.clientHeight - (marks.childElementCount > 0 ? marks.offsetHeight + 8 : 0);
    ganttSvg.style.maxHeight = Math.max(room, 160) + "px";
  }
  window.addEventListener("resize", fitGantt);
  fitGantt();
  setTime(t0);
  requestAnimationFrame(frame);
  // For the browser test and for the curious: the time shown and whether it plays.
  window.workcellView = {
    time: function () {
      return t;
    },
    playing: function () {
      return playing;
    },
  };
})();
