//! The command line every lesson shares (the book's appendix "Interfaces",
//! `book/src/appendix/interfaces.md`).

use std::path::PathBuf;

use clap::Parser;

/// The most timed frames `--frames` accepts.
pub const MAX_FRAMES: u32 = 1000;

#[derive(Parser, Debug, Clone)]
#[command(about = "A lesson of the shadow workbook", disable_version_flag = true)]
pub struct Args {
    /// Render offscreen, write images and report.json, print the report table.
    #[arg(long)]
    pub headless: bool,
    /// A scene file (TOML); the lesson's default scene otherwise.
    #[arg(long, value_name = "FILE.toml")]
    pub scene: Option<PathBuf>,
    #[arg(long, default_value_t = 1280, value_parser = clap::value_parser!(u32).range(16..=8192))]
    pub width: u32,
    #[arg(long, default_value_t = 720, value_parser = clap::value_parser!(u32).range(16..=8192))]
    pub height: u32,
    /// Run only this variant (repeatable). Default: all of the lesson's variants.
    #[arg(long = "variant", value_name = "NAME")]
    pub variants: Vec<String>,
    /// Set a knob of the technique, NAME=VALUE (repeatable): every variant
    /// run that has the knob uses the value. The window's `K` key prints
    /// the knobs it shows in this form.
    #[arg(long = "knob", value_name = "NAME=VALUE", value_parser = crate::run::knobs::parse_knob)]
    pub knobs: Vec<(String, f64)>,
    /// Print the lesson's variants and exit.
    #[arg(long)]
    pub list_variants: bool,
    /// Timed frames per variant after warm-up (1 to 1000); the report quotes
    /// the median. 1000 frames of the slowest lesson on lavapipe take minutes.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=MAX_FRAMES as i64))]
    pub frames: u32,
    /// Untimed warm-up of each timed block, at least (milliseconds; the
    /// first block ten times as long), until frame times settle: see the
    /// book's "Using the workbook". WORKBOOK_WARM_UP_MS is honoured too.
    #[arg(long, value_name = "MS", env = "WORKBOOK_WARM_UP_MS",
          default_value_t = crate::measure::protocol::DEFAULT_WARM_UP_MS,
          value_parser = parse_warm_up_ms)]
    pub warm_up_ms: f64,
    /// Output folder. Default: `out/<lesson>/`
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// vulkan | gl | metal | dx12 (WGPU_BACKEND is honoured too).
    #[arg(long)]
    pub backend: Option<String>,
    /// any (the default: your GPU if you have one) | software (lavapipe or
    /// llvmpipe, as the tests and the grader use) | part of an adapter's
    /// name. WORKBOOK_ADAPTER is honoured too.
    #[arg(long, value_name = "any|software|NAME")]
    pub adapter: Option<String>,
    /// Window: save the window's own picture, overlay included, to this PNG
    /// after `--capture-after` frames and once the live reference's full
    /// figure for that view has come (at most a minute more), then quit.
    #[arg(long, value_name = "FILE.png")]
    pub capture: Option<PathBuf>,
    /// Window: the frames drawn before `--capture` (default 30), or before
    /// quitting without it.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub capture_after: Option<u32>,
    /// Window: the view it opens with.
    #[arg(long, value_enum, value_name = "VIEW")]
    pub view: Option<crate::run::view::View>,
    /// Window: turn the camera around its target at this many degrees per
    /// second, as a steady drag would (-3600 to 3600).
    #[arg(long, value_name = "DEG_PER_S", allow_negative_numbers = true, value_parser = parse_orbit)]
    pub orbit: Option<f64>,
    /// Window: stop `--orbit` after this many seconds (0.1 to 86400).
    #[arg(long, value_name = "S", value_parser = parse_seconds)]
    pub orbit_seconds: Option<f64>,
    /// Window: quit after this many seconds (0.1 to 86400).
    #[arg(long, value_name = "S", value_parser = parse_seconds)]
    pub window_seconds: Option<f64>,
    /// Window: write one JSON line per frame (its time, its cost, the error
    /// figure shown and the view it was computed for): for tests.
    #[arg(long, value_name = "FILE.jsonl")]
    pub window_log: Option<PathBuf>,
    /// Window: no live reference (no error figure, no diff view).
    #[arg(long)]
    pub no_live_reference: bool,
    /// The scene's depth-stencil format: auto (the default: Depth32FloatStencil8
    /// where the adapter has it, else Depth24PlusStencil8) | depth24plus-stencil8
    /// | depth32float-stencil8. WORKBOOK_DEPTH_FORMAT is honoured too.
    #[arg(long, value_name = "auto|depth24plus-stencil8|depth32float-stencil8")]
    pub depth_format: Option<String>,
    /// Also count, per variant, the receivers a rasteriser could flip: draw
    /// it again with the camera moved by 1/16 pixel each way and see which
    /// change (report.json's `fragile`: how far each error figure can move
    /// between two GPUs). WORKBOOK_FRAGILE=1 is honoured too.
    #[arg(long, env = "WORKBOOK_FRAGILE", value_parser = clap::builder::BoolishValueParser::new())]
    pub fragile: bool,
    /// Measure the bounds (`--fragile`) of this variant only (repeatable;
    /// it implies `--fragile` for it, and no other variant's are measured):
    /// the grader's runs ask for the exercise's, the only ones its
    /// snapshot prints. Each must be one of the run's variants.
    #[arg(long = "fragile-variant", value_name = "NAME")]
    pub fragile_variants: Vec<String>,
    /// Time nothing: render each variant only for its images, figures and
    /// counters (the tests and the grader read no times). report.json then
    /// has empty `timing_ms`. WORKBOOK_NO_TIMING=1 is honoured too.
    #[arg(long, env = "WORKBOOK_NO_TIMING", value_parser = clap::builder::BoolishValueParser::new())]
    pub no_timing: bool,
    /// Headless: time the variants and the no-shadow baseline, write
    /// times.json (report.json's times and nothing else) and stop: no
    /// reference, images, error figures or counters. For what reads times
    /// alone (the tests' CPU-time checks).
    #[arg(long)]
    pub times_only: bool,
}

/// The most warm-up `--warm-up-ms` accepts (a minute).
pub const MAX_WARM_UP_MS: f64 = 60_000.0;

/// `--warm-up-ms`: a number of milliseconds from 0 to [`MAX_WARM_UP_MS`].
fn parse_warm_up_ms(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if (0.0..=MAX_WARM_UP_MS).contains(&x) => Ok(x),
        _ => Err(format!("expected milliseconds from 0 to {MAX_WARM_UP_MS}")),
    }
}

/// `--orbit`: degrees per second from -3600 to 3600.
fn parse_orbit(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if (-3600.0..=3600.0).contains(&x) => Ok(x),
        _ => Err("expected degrees per second from -3600 to 3600".to_string()),
    }
}

/// `--window-seconds`: from 0.1 to a day.
fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if (0.1..=86_400.0).contains(&x) => Ok(x),
        _ => Err("expected seconds from 0.1 to 86400".to_string()),
    }
}

impl Args {
    /// The window-only flags given, as the command line spells them.
    pub fn window_flags(&self) -> Vec<&'static str> {
        let given = [
            ("--capture", self.capture.is_some()),
            ("--capture-after", self.capture_after.is_some()),
            ("--view", self.view.is_some()),
            ("--orbit", self.orbit.is_some()),
            ("--orbit-seconds", self.orbit_seconds.is_some()),
            ("--window-seconds", self.window_seconds.is_some()),
            ("--window-log", self.window_log.is_some()),
            ("--no-live-reference", self.no_live_reference),
        ];
        given.into_iter().filter(|g| g.1).map(|g| g.0).collect()
    }

    /// Whether variant `name`'s bounds are measured: the ones
    /// `--fragile-variant` names, else every variant with `--fragile`.
    pub fn measures_bounds(&self, name: &str) -> bool {
        match self.fragile_variants.is_empty() {
            true => self.fragile,
            false => self.fragile_variants.iter().any(|f| f == name),
        }
    }

    /// A flag given with `--times-only` that it leaves nothing to do for
    /// (no timing, bounds of figures it does not measure, the window's).
    pub fn times_only_conflict(&self) -> Option<&'static str> {
        let given = [
            ("--no-timing (or WORKBOOK_NO_TIMING=1)", self.no_timing),
            ("--fragile (or WORKBOOK_FRAGILE=1)", self.fragile),
            ("--fragile-variant", !self.fragile_variants.is_empty()),
        ];
        (given.into_iter().find(|g| g.1).map(|g| g.0)).or(self.window_flags().first().copied())
    }
}

/// The most characters of one quoted value an error line quotes.
pub const MAX_QUOTED_CHARS: usize = 200;
/// The most characters of an error line.
pub const MAX_LINE_CHARS: usize = 1000;

// ANCHOR: clip_values
/// An error line with every quoted value (`"…"`, `'…'` or `` `…` ``) longer
/// than [`MAX_QUOTED_CHARS`] cut to its start and its length, and the line
/// itself cut at [`MAX_LINE_CHARS`]: a 100 000-character `--variant` gets
/// one readable line, not a screenful.
pub fn clip_values(line: &str) -> String {
    let chars: Vec<char> = line.chars().collect();
    let mut out = String::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        // A quote opens a value only at the start of a word: the
        // apostrophe of "lesson's" does not.
        let opens = i == 0 || !chars[i - 1].is_alphanumeric();
        if !matches!(c, '"' | '\'' | '`') || !opens {
            out.push(c);
            i += 1;
            continue;
        }
        // The closing quote, skipping backslash escapes.
        let mut j = i + 1;
        while j < chars.len() && chars[j] != c {
            j += if chars[j] == '\\' { 2 } else { 1 };
        }
        let end = j.min(chars.len());
        let inner = &chars[i + 1..end.max(i + 1)];
        out.push(c);
        if inner.len() > MAX_QUOTED_CHARS {
            out.extend(&inner[..MAX_QUOTED_CHARS / 2]);
            out += &format!("… ({} characters)", inner.len());
        } else {
            out.extend(inner);
        }
        if end < chars.len() {
            out.push(c);
        }
        i = end + 1;
    }
    let n = out.chars().count();
    if n > MAX_LINE_CHARS {
        let cut: String = out.chars().take(MAX_LINE_CHARS).collect();
        return format!("{cut}… ({n} characters in all)");
    }
    out
}
// ANCHOR_END: clip_values

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_quoted_values_are_cut_and_short_lines_kept() {
        let short = "--variant: unknown variant \"res_9\" (known: res_256)";
        assert_eq!(clip_values(short), short);
        let long = format!(
            "--variant: unknown variant \"{}\" (known: res_256, res_512)",
            "x".repeat(100_000)
        );
        let clipped = clip_values(&long);
        assert!(clipped.chars().count() < 300, "{}", clipped.len());
        assert!(
            clipped.starts_with("--variant: unknown variant \"xxx"),
            "{clipped}"
        );
        assert!(
            clipped.contains("(100000 characters)\" (known: res_256, res_512)"),
            "{clipped}"
        );
        // Single quotes (clap), backticks, escapes inside, and an unclosed quote.
        let clap = format!(
            "error: invalid value '{}' for '--warm-up-ms <MS>'",
            "9".repeat(5000)
        );
        assert!(clip_values(&clap).ends_with("(5000 characters)' for '--warm-up-ms <MS>'"));
        let esc = format!("name \"a\\\"{}\" is bad", "y".repeat(300));
        assert!(
            clip_values(&esc).ends_with("(303 characters)\" is bad"),
            "{}",
            clip_values(&esc)
        );
        let open = format!("bad `{}", "z".repeat(1000));
        assert!(clip_values(&open).chars().count() < 300);
        // Apostrophes in words are not quotes.
        let prose = format!("the lesson's {} wgpu's", "v ".repeat(200));
        assert_eq!(clip_values(&prose), prose);
        // Unquoted, the line itself is cut.
        let bare = "w ".repeat(5000);
        let cut = clip_values(&bare);
        assert!(cut.ends_with("(10000 characters in all)") && cut.chars().count() < 1100);
    }
}
