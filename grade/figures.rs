//! What the grader reads from a lesson's report: a variant's figures and
//! counters, the bound a run measured for them, a target resolved on the
//! run, and a figure printed with the decimals it needs.

use serde_json::Value;

use crate::spec::{Side, Target};

/// A run's variant by name.
pub fn variant<'a>(report: &'a Value, name: &str) -> Option<&'a Value> {
    report["variants"]
        .as_array()?
        .iter()
        .find(|v| v["name"] == name)
}

/// A metric of a variant: an error figure, `counters.<name>` or
/// `camera_path.<name>` (on a scene with a `[camera_path]`).
pub fn metric(report: &Value, variant_name: &str, metric: &str) -> Option<f64> {
    let v = variant(report, variant_name)?;
    match metric.split_once('.') {
        Some(("counters", c)) => v["counters"][c].as_f64(),
        Some(("camera_path", c)) => v["camera_path"][c].as_f64(),
        _ => v["error"][metric].as_f64(),
    }
}

/// ` ±B`: how far figure `field` of `variant_name` may move on another
/// adapter, as the run measured it (report.json's `fragile.bounds`, times
/// `scale`, rounded up to two decimals); empty when it measured none.
pub fn bound(report: &Value, variant_name: &str, field: &str, scale: f64) -> String {
    variant(report, variant_name)
        .and_then(|v| v["fragile"]["bounds"][field].as_f64())
        .map_or(String::new(), |b| {
            format!(
                " ±{:.2}",
                (b * scale * 100.0 - 1e-9).ceil().max(0.0) / 100.0
            )
        })
}

/// Prints a figure with as many decimals as small figures need.
pub fn fmt(x: f64) -> String {
    if x == x.trunc() && x.abs() < 1e15 {
        format!("{x:.0}")
    } else if x.abs() >= 100.0 {
        format!("{x:.1}")
    } else if x.abs() >= 0.1 {
        format!("{x:.2}")
    } else {
        format!("{x:.4}")
    }
}

/// Resolves a target on one run: its number and how it reads.
pub fn resolve(t: &Target, report: &Value, metric_name: &str) -> Option<(f64, String)> {
    let op = match t.side {
        Side::AtMost => "<=",
        Side::AtLeast => ">=",
    };
    match (t.value, t.variant) {
        (Some(v), _) => Some((v, format!("{op} {}", fmt(v)))),
        (None, Some(name)) => {
            let base = metric(report, name, metric_name)?;
            let v = base * t.factor + t.slack;
            let mut text = format!("{op} {} ({name} {}", fmt(v), fmt(base));
            if t.factor != 1.0 {
                text += &format!(" x {}", fmt(t.factor));
            }
            if t.slack != 0.0 {
                text += &format!(" + {}", fmt(t.slack));
            }
            text.push(')');
            Some((v, text))
        }
        (None, None) => None,
    }
}
