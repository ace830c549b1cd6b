//! Reading a lesson's report.json: a variant ([`variant`]), its error
//! figures ([`error`], [`misclassified`]) and counters ([`counter`]), and
//! the snapshot lines made of them, each figure with the bound the run
//! measured for it ([`error_line`], [`bound`], [`counter_lines`]).

use crate::portable;
use crate::run::LessonRun;

pub fn variant<'a>(report: &'a serde_json::Value, name: &str) -> &'a serde_json::Value {
    report["variants"]
        .as_array()
        .and_then(|vs| vs.iter().find(|v| v["name"] == name))
        .unwrap_or_else(|| panic!("variant {name} missing from report.json"))
}

/// One error figure of one variant (`"misclassified_pct"`, `"false_lit_pct"`, ...).
pub fn error(report: &serde_json::Value, variant_name: &str, key: &str) -> f64 {
    variant(report, variant_name)["error"][key]
        .as_f64()
        .unwrap_or_else(|| panic!("{variant_name}: error.{key} missing"))
}

/// A variant's misclassified %, the figure most pass criteria use.
pub fn misclassified(run: &LessonRun, variant_name: &str) -> f64 {
    error(&run.report, variant_name, "misclassified_pct")
}

/// One counter of one variant (`"taps"`, `"volume_fragments"`, ...).
pub fn counter(report: &serde_json::Value, variant_name: &str, key: &str) -> u64 {
    variant(report, variant_name)["counters"][key]
        .as_u64()
        .unwrap_or_else(|| panic!("{variant_name}: counters.{key} missing"))
}

/// One variant's error figures, rounded for a stable snapshot, each with
/// its bound when the run measured one ([`bound`]).
pub fn error_line(v: &serde_json::Value, decimals: usize) -> String {
    let e = &v["error"];
    let f = |k: &str| e[k].as_f64().unwrap_or(f64::NAN);
    let b = |k: &str| bound(v, k, 1.0, decimals);
    format!(
        "{:<14} misclassified {:>6.d$}%{}  false shadow {:>6.d$}%{}  false lit {:>6.d$}%{}",
        v["name"].as_str().unwrap_or("?"),
        f("misclassified_pct"),
        b("misclassified_pct"),
        f("false_shadow_pct"),
        b("false_shadow_pct"),
        f("false_lit_pct"),
        b("false_lit_pct"),
        d = decimals
    )
}

/// ` ±B`: how far error figure `field` (an `ErrorStats` or `SoftError`
/// field) of variant `v` may move on another adapter, as the run measured
/// it (`--fragile`, report.json's `fragile.bounds`; see
/// `common::reference::fragile`), times `scale` (100 for a fraction
/// printed in percent), rounded up to `decimals`. Empty when the run
/// measured none. `tolerance::compare` allows the committed text's bound.
/// A figure whose bound is too wide for it to be compared (as printed, to
/// `decimals`: [`portable::portable`]) gets
/// ` (not portable: ±B, above 10%)` instead, and is compared by its side.
pub fn bound(v: &serde_json::Value, field: &str, scale: f64, decimals: usize) -> String {
    let Some(b) = v["fragile"]["bounds"][field].as_f64() else {
        return String::new();
    };
    let step = 10f64.powi(-(decimals as i32));
    let up = (b * scale / step - 1e-9).ceil().max(0.0) * step;
    let text = format!("{up:.decimals$}");
    // The figure as the snapshot prints it.
    let figure = v["error"][field].as_f64().map(|f| {
        let printed = format!("{:.decimals$}", f * scale);
        printed.parse::<f64>().unwrap_or(f64::NAN)
    });
    match figure {
        Some(f) if !portable::portable(f, up) => {
            portable::not_portable(&text, portable::portable_side(f))
        }
        _ => format!(" ±{text}"),
    }
}

/// ` ±N`: how far counter `key` of variant `v` moved when the run drew it
/// again with the camera moved (`fragile.counters`), or empty.
pub fn counter_bound(v: &serde_json::Value, key: &str) -> String {
    match v["fragile"]["counters"][key].as_u64() {
        Some(n) => format!(" ±{n}"),
        None => String::new(),
    }
}

/// The snapshot's cost counters: for every variant, `keys` that it has
/// (keys a variant lacks, such as a skipped variant's, are left out),
/// compared as [`crate::tolerance`] says (most exactly).
pub fn counter_lines(report: &serde_json::Value, keys: &[&str]) -> String {
    let mut out = String::from("\ncounters:\n");
    for v in report["variants"].as_array().into_iter().flatten() {
        let c = &v["counters"];
        let parts: Vec<String> = keys
            .iter()
            .filter_map(|k| {
                c[*k]
                    .as_u64()
                    .map(|n| format!("{k} {n}{}", counter_bound(v, k)))
            })
            .collect();
        out += &format!(
            "{:<18} {}\n",
            v["name"].as_str().unwrap_or("?"),
            parts.join("  ")
        );
    }
    out
}
