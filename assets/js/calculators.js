// The lessons' calculators (_includes/calculator.html): each <form data-calculator> is
// worked out again whenever one of its inputs changes. The formulas are the ones the page
// states, written as the page's Python writes them, so both give the same numbers.
(function () {
  "use strict";

  // ---- Numbers as the pages print them ------------------------------------------
  // `decimals` is what the page's Python prints. Numbers below 1 get more, up to four,
  // to keep three significant digits (0.833 rad/s rather than 0.8); numbers that would
  // still read as zero (rounding errors such as 1e-17) keep the page's decimals.
  function decimalsFor(x, decimals) {
    if (Math.abs(x) >= 1 || Math.abs(x) < 5e-5) return decimals;
    return Math.max(decimals, Math.min(4, 2 - Math.floor(Math.log10(Math.abs(x)))));
  }

  function number(x, decimals) {
    var text = x.toFixed(decimalsFor(x, decimals));
    return /^-0(\.0*)?$/.test(text) ? text.slice(1) : text;  // no "-0.00"
  }

  function degrees(radians) {
    return radians * 180 / Math.PI;
  }

  function radians(degrees) {
    return degrees * Math.PI / 180;
  }

  function angleText(rad) {
    return number(degrees(rad), 2) + "° (" + number(rad, 4) + " rad)";
  }

  // ---- The calculators --------------------------------------------------------
  // inputs: a check per input that has limits (returns what is wrong, or ""); every
  //         input must also be a finite number.
  // results: per <output> name, the inputs it needs and how to get it from them:
  //          { value, text }, with `special: true` when a value that is not a finite
  //          number is the right answer (an infinite radius, no direction).

  function above(limit, message) {
    return function (x) { return x > limit ? "" : message; };
  }

  // Equation 4 as examples/example_5/scripts/ackermann.py's knuckle_angles writes it.
  function knuckleAngles(phi, l, w) {
    var s = Math.sin(phi), c = Math.cos(phi);
    return { left: Math.atan2(2 * l * s, 2 * l * c - w * s),
             right: Math.atan2(2 * l * s, 2 * l * c + w * s) };
  }

  function wheelAngle(v, inner) {
    var phi = radians(v.phi);
    var angles = knuckleAngles(phi, v.l, v.w);
    var left = inner ? phi > 0 : phi < 0;
    var value = left ? angles.left : angles.right;
    var side = phi === 0 ? "straight ahead" : (left ? "left wheel" : "right wheel");
    return { value: value, text: angleText(value) + ", " + side };
  }

  function armTip(v) {
    var t1 = radians(v.t1), t12 = radians(v.t1) + radians(v.t2);
    return { x: v.l1 * Math.cos(t1) + v.l2 * Math.cos(t12),
             y: v.l1 * Math.sin(t1) + v.l2 * Math.sin(t12) };
  }

  function metres(x) {
    return { value: x, text: number(x, 3) + " m" };
  }

  var ARM = ["l1", "l2", "t1", "t2"];

  var KINDS = {
    "deg-rad": {
      inputs: {},
      results: {
        radians: { from: ["deg"], compute: function (v) {
          var x = v.deg * Math.PI / 180;
          return { value: x, text: number(x, 4) + " rad" };
        } },
        degrees: { from: ["rad"], compute: function (v) {
          var x = degrees(v.rad);
          return { value: x, text: number(x, 2) + "°" };
        } }
      }
    },
    rpm: {
      inputs: {},
      results: {
        omega: { from: ["rpm"], compute: function (v) {
          var x = 2 * Math.PI / 60 * v.rpm;
          return { value: x, text: number(x, 2) + " rad/s" };
        } }
      }
    },
    "wheel-speed": {
      inputs: { r: above(0, "The wheel radius r must be more than 0 m.") },
      results: {
        omega: { from: ["v", "r"], compute: function (v) {
          var x = v.v / v.r;
          return { value: x, text: number(x, 1) + " rad/s" };
        } }
      }
    },
    ackermann: {
      inputs: {
        l: above(0, "The wheelbase l must be more than 0 m."),
        w: function (x) { return x >= 0 ? "" : "The track w cannot be negative."; },
        phi: function (x) {
          return Math.abs(x) < 90 ? "" : "The steering angle Φ must be between -90° and 90°.";
        }
      },
      results: {
        radius: { from: ["l", "phi"], compute: function (v) {
          var phi = radians(v.phi);
          var r = v.l / Math.tan(phi);
          if (phi === 0) {
            return { value: Infinity, text: "infinite: the car drives straight", special: true };
          }
          return { value: r, text: number(Math.abs(r), 3) + " m, turning "
                                   + (phi > 0 ? "left" : "right") };
        } },
        inner: { from: ["l", "w", "phi"], compute: function (v) { return wheelAngle(v, true); } },
        outer: { from: ["l", "w", "phi"], compute: function (v) { return wheelAngle(v, false); } }
      }
    },
    "arm-reach": {
      inputs: {
        l1: above(0, "The middle arm's length L1 must be more than 0 m."),
        l2: above(0, "The end arm's length L2 must be more than 0 m.")
      },
      results: {
        x: { from: ARM, compute: function (v) { return metres(armTip(v).x); } },
        y: { from: ARM, compute: function (v) { return metres(armTip(v).y); } },
        distance: { from: ARM, compute: function (v) {
          var tip = armTip(v);
          return metres(Math.hypot(tip.x, tip.y));
        } },
        angle: { from: ARM, compute: function (v) {
          var tip = armTip(v);
          // At the pivot itself (L1 = L2, θ2 = ±180°) no direction is meaningful.
          if (Math.hypot(tip.x, tip.y) < 1e-9 * (v.l1 + v.l2)) {
            return { value: NaN, text: "none: the fingertips are on the pivot", special: true };
          }
          var x = degrees(Math.atan2(tip.y, tip.x));
          return { value: x, text: number(x, 2) + "°" };
        } }
      }
    }
  };

  // ---- Reading the form and writing the results ----------------------------------

  function labelText(input) {
    return input.labels.length ? input.labels[0].textContent.trim() : input.name;
  }

  // Each input's number, or what is wrong with it.
  function read(form, kind) {
    var values = {}, problems = {};
    Array.prototype.forEach.call(form.querySelectorAll("input"), function (input) {
      var x = input.value.trim() === "" ? NaN : Number(input.value);
      var check = kind.inputs[input.name];
      var problem = Number.isFinite(x) ? (check ? check(x) : "")
                                       : "Enter a number for “" + labelText(input) + "”.";
      if (problem) problems[input.name] = problem;
      else values[input.name] = x;
    });
    return { values: values, problems: problems };
  }

  function update(form, kind) {
    var message = form.querySelector(".calc-message");
    var entered = read(form, kind);
    var problems = Object.keys(entered.problems).map(function (name) {
      return entered.problems[name];
    });

    Object.keys(kind.results).forEach(function (name) {
      var result = kind.results[name];
      var output = form.querySelector("output[name='" + name + "']");
      var ready = result.from.every(function (input) { return input in entered.values; });
      var shown = ready ? result.compute(entered.values) : null;
      if (shown && !shown.special && !Number.isFinite(shown.value)) {
        problems.push("The numbers are too large to work out.");
        shown = null;
      }
      output.textContent = shown ? shown.text : "–";
      if (shown && !Number.isNaN(shown.value)) output.dataset.value = String(shown.value);
      else delete output.dataset.value;
    });

    Array.prototype.forEach.call(form.querySelectorAll("input"), function (input) {
      if (entered.problems[input.name]) {
        input.setAttribute("aria-invalid", "true");
        input.setAttribute("aria-describedby", message.id);
      } else {
        input.removeAttribute("aria-invalid");
        input.removeAttribute("aria-describedby");
      }
    });
    message.textContent = problems.filter(function (p, i) {
      return problems.indexOf(p) === i;
    }).join(" ");
  }

  function setUp(form) {
    var name = form.closest("[data-calculator]").dataset.calculator;
    var kind = KINDS[name];
    if (!kind) {
      // An include without its formulas here: say so where the page tests look.
      console.error("calculators.js has no calculator called " + name);
      return;
    }
    form.addEventListener("input", function () { update(form, kind); });
    // Enter in a field would otherwise reload the page with the values in its address.
    form.addEventListener("submit", function (event) { event.preventDefault(); });
    update(form, kind);
  }

  Array.prototype.forEach.call(document.querySelectorAll(".calculator form"), setUp);
})();
