//! One screenshot of each lesson's window for its chapter: the window's
//! own picture (`--capture`, overlay included), taken on a private Xvfb
//! (`common::run::display`) once the live reference's full figure for the
//! view has come. Each chapter shows `figures/window/lesson_NN.png` with
//! `generated/window/lesson_NN.md` as its caption, written from the
//! window's own log. The capture is made opaque for the page
//! ([`crate::figures::prepare`]).

use std::path::Path;

use anyhow::{bail, Context, Result};
use common::run::display::Display;

use crate::runner::Runner;

/// The picture's size (the window's, in pixels).
pub const SIZE: (u32, u32) = (960, 540);
/// Frames before the capture (then it waits for the full figure).
const FRAMES: u32 = 5;

/// One chapter's shot: the lesson, the variant, the view, and what the
/// caption says the view shows.
pub struct Shot {
    pub lesson: &'static str,
    pub variant: &'static str,
    pub view: &'static str,
    shows: &'static str,
}

/// The same views live in the book's pages ([`crate::web`]).
pub const SHOTS: [Shot; 10] = [
    Shot { lesson: "lesson_01", variant: "res_1024", view: "diff", shows: "the difference against the exact reference: red false shadow, green false lit" },
    Shot { lesson: "lesson_02", variant: "bias_1tx", view: "diff", shows: "the difference against the exact reference: red false shadow (acne), green false lit (Peter Panning)" },
    Shot { lesson: "lesson_03", variant: "pcf_3x3", view: "diff", shows: "the difference against the exact reference along the filtered edges" },
    Shot { lesson: "lesson_04", variant: "depth_1024", view: "buffer", shows: "the lesson's buffer: the cube map unfolded as a cross" },
    Shot { lesson: "lesson_05", variant: "zpass_quads", view: "diff", shows: "the difference against the exact reference" },
    Shot { lesson: "lesson_06", variant: "zfail_quads", view: "diff", shows: "the difference against the exact reference" },
    Shot { lesson: "lesson_07", variant: "reversed_z", view: "frame", shows: "the frame" },
    Shot { lesson: "lesson_08", variant: "bounds_scissor", view: "frame", shows: "the frame, with the knobs that switch the scissor, the depth bounds and the culling" },
    Shot { lesson: "lesson_09", variant: "k4", view: "buffer", shows: "the lesson's buffer: the cascade each pixel samples" },
    Shot { lesson: "lesson_10", variant: "pcss", view: "dv", shows: "ΔV, the GPU's visibility less the exact visible fraction of the light, on the receivers: blue where the GPU is darker, red where it is lighter, white where the two agree" },
];

/// Takes every chapter's shot (or only `only`'s, a lesson) into
/// `figures/window/` and writes its figure into `generated/window/`.
pub fn write_all(
    runner: &Runner,
    figures: &Path,
    generated: &Path,
    backend: &str,
    adapter: &str,
    only: Option<&str>,
) -> Result<()> {
    if let Some(l) = only {
        if !SHOTS.iter().any(|s| s.lesson == l) {
            bail!("--only: no window shot of {l:?}");
        }
    }
    let display = Display::open()?;
    let (pics, texts) = (figures.join("window"), generated.join("window"));
    for d in [&pics, &texts] {
        std::fs::create_dir_all(d).with_context(|| format!("cannot create {}", d.display()))?;
    }
    let work = std::env::temp_dir().join(format!("workbook-window-shots-{}", std::process::id()));
    std::fs::create_dir_all(&work)?;
    for shot in SHOTS.iter().filter(|s| only.is_none_or(|l| l == s.lesson)) {
        let png = pics.join(format!("{}.png", shot.lesson));
        let log = work.join(format!("{}.jsonl", shot.lesson));
        let mut cmd = std::process::Command::new(runner.binary(shot.lesson));
        display.apply(&mut cmd);
        let (w, h) = (SIZE.0.to_string(), SIZE.1.to_string());
        cmd.args(["--width", &w, "--height", &h, "--variant", shot.variant])
            .args([
                "--view",
                shot.view,
                "--backend",
                backend,
                "--adapter",
                adapter,
            ])
            .args(["--capture-after", &FRAMES.to_string()])
            .arg("--capture")
            .arg(&png)
            .arg("--window-log")
            .arg(&log)
            .arg("--out")
            .arg(&work);
        let out = cmd
            .output()
            .with_context(|| format!("cannot run {}", shot.lesson))?;
        if !out.status.success() {
            let err = String::from_utf8_lossy(&out.stderr);
            bail!("{}'s window: {}", shot.lesson, err.trim());
        }
        // Opaque for the white page, like every figure (`figures.rs`).
        let dest = format!("window/{}.png", shot.lesson);
        let mut counts = std::collections::BTreeMap::new();
        crate::figures::prepare_file(&png, &dest, &png, &mut counts)?;
        let text = std::fs::read_to_string(&log).context("the window's log")?;
        let last: serde_json::Value =
            serde_json::from_str(text.lines().last().context("the window drew no frame")?)?;
        let figure = caption(shot, &last)?;
        let md = texts.join(format!("{}.md", shot.lesson));
        std::fs::write(&md, figure).with_context(|| format!("cannot write {}", md.display()))?;
    }
    let _ = std::fs::remove_dir_all(&work);
    Ok(())
}

/// The chapter's caption, from the window's log.
fn caption(shot: &Shot, last: &serde_json::Value) -> Result<String> {
    let logged = last["adapter"].as_str().context("the log's adapter")?;
    // The log names it `NAME (Backend)`: the book names it as its tables do.
    let adapter = match logged.rsplit_once(" (") {
        Some((name, backend)) if backend.ends_with(')') => {
            crate::record::adapter_label(name, backend.trim_end_matches(')'))
        }
        _ => logged.to_string(),
    };
    let e = &last["error"];
    let pct = |k: &str| e[k].as_f64().context("the log's error figure");
    if last["error_current"] != true || e["level"] != "full" {
        bail!(
            "{}: the capture came before the full figure of its view",
            shot.lesson
        );
    }
    let (w, h) = SIZE;
    // An area light's figures (lesson 10), where the log has them.
    let soft = match (
        e["penumbra_mean_abs"].as_f64(),
        e["light_bleeding_pct"].as_f64(),
    ) {
        (Some(p), Some(b)) => format!(
            ", and inside the penumbra mean |ΔV| {:.3} %, bleeding {b:.3} % of the umbra",
            100.0 * p
        ),
        _ => String::new(),
    };
    Ok(format!(
        "The window of <code>cargo run --release --bin {lesson} -- --variant {variant} --view {view}</code> ({w}×{h}, on {adapter}, captured with <code>--capture</code> after {frames} frames, once the full figure had come): the overlay at the top left, and {shows}. The overlay's figure, against the exact reference: misclassified {m:.3} %, false shadow {fs:.3} %, false lit {fl:.3} %{soft} (the headless report's figures for the same variant and size; <code>tests/window.rs</code> checks that the two agree).\n",
        lesson = shot.lesson,
        variant = shot.variant,
        view = shot.view,
        frames = FRAMES,
        shows = shot.shows,
        m = pct("misclassified_pct")?,
        fs = pct("false_shadow_pct")?,
        fl = pct("false_lit_pct")?,
    ))
}
