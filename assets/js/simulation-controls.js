// The lesson's own inputs in the Simulate mode (assets/js/simulation.js): one number field
// per input, each with its unit and its range, from the practice's simulate.json (written by
// course/browser_models.py from the lesson script and the package). A value outside the
// range is refused in the field itself: it is marked invalid, said why, and not sent.

const RAD = "rad";

function label(joint) {
  return joint.replace(/_joint$/, "").replaceAll("_", " ");
}

// What the reader may set for one lesson: [{name, label, unit, min, max, step}].
export function lessonInputs(lesson) {
  if (lesson.kind === "car") {
    const [slow, fast] = lesson.speed_range;
    const [right, left] = lesson.steering_range;
    return [
      { name: "speed", label: "speed of the rear axle's centre", unit: "m/s", min: slow,
        max: fast, step: 0.1 },
      { name: "steering", label: "centre steering angle, positive to the left", unit: RAD,
        min: right, max: left, step: 0.01 }];
  }
  if (lesson.kind === "pulse") {
    const [low, high] = lesson.torque_range;
    const inputs = lesson.joints.map((joint) => ({
      name: `torque:${joint}`, label: `${label(joint)} wheel torque`, unit: "N·m",
      min: low, max: high, step: 0.1 }));
    inputs.push(
      { name: "period", label: "pulse period", unit: "s", min: 1, max: 60, step: 0.5 },
      { name: "pulse", label: "pulse length", unit: "s", min: 0, max: 60, step: 0.1,
        below: "period" });
    if (lesson.friction) {
      const [fLow, fHigh] = lesson.friction_range;
      for (const joint of lesson.joints) {
        inputs.push({ name: `friction:${joint}`, label: `${label(joint)} joint friction`,
          unit: "N·m", min: fLow, max: fHigh, step: 0.05 });
      }
    }
    return inputs;
  }
  const unit = lesson.unit;
  const per = unit === RAD ? "N·m/rad" : "N/m";
  const inputs = [];
  for (const c of lesson.controllers) {
    const name = c.name.replace(/_controller$/, "").replaceAll("_", " ");
    inputs.push({ name: `setpoint:${c.name}`, label: `${name} set point`, unit,
      min: c.limits.lower, max: c.limits.upper, step: 0.01 });
    const gains = { p: per, i: `${per}/s`, d: `${per}·s` };
    for (const [gain, gainUnit] of Object.entries(gains)) {
      inputs.push({ name: `${gain}:${c.name}`, label: `${name} ${gain.toUpperCase()} gain`,
        unit: gainUnit, min: 0, max: 10 * c.pid[gain], step: "any" });
    }
  }
  return inputs;
}

function number(value) {
  return String(Math.round(value * 1e4) / 1e4).replace("-", "\u2212");
}

// Builds the fields into `fieldset`; `send(name, value)` gets each accepted value.
export function buildControls(fieldset, lesson, values, send, idPrefix) {
  const fields = {};
  for (const input of lessonInputs(lesson)) {
    const id = `${idPrefix}-${input.name.replace(/[^a-z0-9]+/gi, "-")}`;
    const row = document.createElement("div");
    row.className = "simulation-input";
    const labelElement = document.createElement("label");
    labelElement.htmlFor = id;
    labelElement.textContent = `${input.label} (${input.unit})`;
    const field = document.createElement("input");
    Object.assign(field, { type: "number", id, min: input.min, max: input.max,
      step: input.step, value: values[input.name] });
    field.dataset.name = input.name;
    const range = document.createElement("span");
    range.className = "simulation-range";
    range.id = `${id}-range`;
    range.textContent = `${number(input.min)} to ${number(input.max)} ${input.unit}`;
    field.setAttribute("aria-describedby", range.id);
    const refuse = (why) => {
      field.setAttribute("aria-invalid", "true");
      range.textContent = why;
      row.dataset.refused = "true";
    };
    field.addEventListener("change", () => {
      const value = Number(field.value);
      const upper = input.below ? Math.min(input.max, Number(fields[input.below].value)) : input.max;
      if (field.value === "" || !Number.isFinite(value)) {
        refuse(`Refused: enter a number from ${number(input.min)} to ${number(upper)} ${input.unit}.`);
      } else if (value < input.min || value > upper) {
        refuse(`Refused: ${number(value)} ${input.unit} is outside ${number(input.min)} to `
          + `${number(upper)} ${input.unit}${input.below ? ` (no longer than the ${input.below})` : ""}.`);
      } else {
        field.removeAttribute("aria-invalid");
        delete row.dataset.refused;
        range.textContent = `${number(input.min)} to ${number(input.max)} ${input.unit}`;
        send(input.name, value);
      }
    });
    row.append(labelElement, field, range);
    fieldset.append(row);
    fields[input.name] = field;
  }
  return fields;
}
