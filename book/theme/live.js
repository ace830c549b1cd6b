// The live lessons. A chapter's window screenshot (its figure holds a
// `.live-bar`) becomes the lesson itself when the reader asks: the
// lesson's own code, compiled to WebAssembly (`workbook web`), drawing on
// the reader's GPU through WebGPU, with the window's overlay and its error
// figure against the exact reference, computed in the page's own worker
// thread (a Web Worker), so that the page never waits for it.
//
// Nothing loads until the button is pressed; a browser without WebGPU keeps
// the screenshot and says why. `?live` in the address starts the page's
// lesson at once (the book's check, `.ci/web-check`, uses it).
(function () {
  "use strict";
  const root = typeof path_to_root === "string" ? path_to_root : "";
  // A module import needs an address, not a bare path.
  const at = (path) => new URL(root + path, document.baseURI).href;

  function noWebGpu(bar, why) {
    bar.querySelector("button").disabled = true;
    bar.querySelector(".live-note").textContent =
      "This browser " + why + ", so the lesson cannot run in the page; " +
      "the screenshot below is the desktop window. Chrome and Edge (113 and later), Firefox (141 and later, " +
      "on Windows) and Safari (26 and later) have WebGPU.";
  }

  async function start(bar) {
    if (document.getElementById("workbook-canvas")) {
      return; // one live lesson per page
    }
    const figure = bar.closest("figure");
    const img = figure.querySelector("img");
    const note = bar.querySelector(".live-note");
    const button = bar.querySelector("button");
    button.disabled = true;
    // WebGPU without an adapter (no usable GPU, or one the browser blocks):
    // the screenshot stays.
    if (!(await navigator.gpu.requestAdapter().catch(() => null))) {
      noWebGpu(bar, "has WebGPU but offers it no adapter (no usable GPU here)");
      return;
    }
    const canvas = document.createElement("canvas");
    canvas.id = "workbook-canvas";
    canvas.className = "live-canvas";
    canvas.dataset.args = bar.dataset.args;
    // The lesson's reference worker starts the same module from the same
    // glue, with the same flags (common/src/run/window/live_page.rs).
    canvas.dataset.lesson = bar.dataset.lesson;
    canvas.dataset.glue = at("web/workbook_web.js");
    canvas.tabIndex = 0;
    // The lesson's keys are the lesson's: mdBook's own (arrows turn the
    // page, S searches) must not see them.
    canvas.addEventListener("keydown", (e) => e.stopPropagation());
    const error = document.createElement("p");
    error.id = "workbook-error";
    error.className = "live-error";
    img.replaceWith(canvas);
    canvas.after(error);
    // The caption was the screenshot's: say what is on screen now.
    const caption = figure.querySelector("figcaption");
    if (caption) {
      const now = document.createElement("strong");
      now.textContent =
        "Running live in this page, on your GPU: the overlay's figure is computed here, against the exact reference. " +
        "The screenshot this replaced: ";
      caption.prepend(now);
    }
    note.textContent = "Loading the lessons (" + bar.dataset.size + ")…";
    try {
      const glue = await import(at("web/workbook_web.js"));
      const response = await fetch(at("web/workbook_web_bg.wasm.gz"));
      if (!response.ok) {
        throw new Error("web/workbook_web_bg.wasm.gz: " + response.status + " " + response.statusText);
      }
      const wasm = await new Response(
        response.body.pipeThrough(new DecompressionStream("gzip"))
      ).arrayBuffer();
      await glue.default({ module_or_path: wasm });
      note.textContent = bar.dataset.keys;
      glue.run_lesson(bar.dataset.lesson);
      canvas.focus();
    } catch (e) {
      error.textContent = "error: " + bar.dataset.lesson + ": " + e;
      console.error(error.textContent);
    }
  }

  const bars = document.querySelectorAll(".live-bar");
  bars.forEach((bar) => {
    if (!navigator.gpu) {
      noWebGpu(bar, "has no WebGPU (navigator.gpu is missing)");
      return;
    }
    bar.querySelector("button").addEventListener("click", () => start(bar));
  });
  if (bars.length && navigator.gpu && new URLSearchParams(location.search).has("live")) {
    start(bars[0]);
  }
})();
