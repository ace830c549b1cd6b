//! The plots' unit tests: the Pareto front, the log-log slope, the axes'
//! ticks and labels, and a plot written twice byte for byte the same.

use super::*;

use super::axis::{fmt_exact, Axis};

fn pt(label: &str, ms: f64, error_pct: f64) -> Point {
    Point {
        label: label.into(),
        ms,
        ms_low: ms * 0.9,
        ms_high: ms * 1.1,
        error_pct,
    }
}

#[test]
fn pareto_front_excludes_dominated_points_and_sorts_by_time() {
    let points = vec![
        pt("slow_exact", 9.0, 0.0),
        pt("dominated", 5.0, 2.0), // beaten by "mid" on both
        pt("fast_rough", 1.0, 5.0),
        pt("mid", 4.0, 1.0),
        pt("same_time_worse", 4.0, 1.5), // same time as "mid", more error
        pt("broken", f64::NAN, 0.0),
    ];
    assert_eq!(pareto_front(&points), vec![2, 3, 0]);
}

#[test]
fn pareto_front_keeps_ties_and_handles_empty() {
    let points = vec![pt("a", 2.0, 1.0), pt("b", 2.0, 1.0), pt("c", 3.0, 1.0)];
    assert_eq!(pareto_front(&points), vec![0, 1]);
    assert!(pareto_front(&[]).is_empty());
}

#[test]
fn loglog_slope_measures_the_order() {
    let xs = [1.0, 2.0, 4.0, 8.0, 16.0];
    let square: Vec<f64> = xs.iter().map(|x| 3.0 * x * x).collect();
    assert!((loglog_slope(&xs, &square) - 2.0).abs() < 1e-12);
    let linear: Vec<f64> = xs.iter().map(|x| 0.5 * x).collect();
    assert!((loglog_slope(&xs, &linear) - 1.0).abs() < 1e-12);
    let constant = [7.0; 5];
    assert!(loglog_slope(&xs, &constant).abs() < 1e-12);
    let n_log_n: Vec<f64> = xs.iter().map(|x| x * x.ln().max(1.0)).collect();
    let s = loglog_slope(&xs, &n_log_n);
    assert!(s > 1.0 && s < 1.5, "{s}");
    assert!(loglog_slope(&[1.0], &[1.0]).is_nan());
    assert!(loglog_slope(&[2.0, 2.0], &[1.0, 3.0]).is_nan());
}

#[test]
fn log_axis_ticks_are_round_numbers() {
    let a = Axis::log(0.001, 5.0);
    let labels: Vec<String> = a.bold.iter().map(|t| a.label(*t)).collect();
    assert_eq!(labels, ["0.001", "0.01", "0.1", "1"]);
    let b = Axis::log(0.3, 2.0);
    let labels: Vec<String> = b.bold.iter().map(|t| b.label(*t)).collect();
    assert_eq!(labels, ["0.5", "1", "2"]);
}

#[test]
fn scaling_x_axis_labels_the_data_ends() {
    let xs = [256.0, 512.0, 1024.0, 2048.0, 4096.0];
    let a = Axis::log(256.0, 4096.0).ticks_at(&xs);
    let labels: Vec<String> = a.bold.iter().map(|t| a.label(*t)).collect();
    assert_eq!(labels, ["256", "512", "1 024", "2 048", "4 096"]);
    // Too many values for a label each: round ticks plus both ends.
    let many: Vec<f64> = (0..40).map(|k| 3.0 * 1.3f64.powi(k)).collect();
    let b = Axis::log(many[0], many[39]).ticks_at(&many);
    let labels: Vec<String> = b.bold.iter().map(|t| b.label(*t)).collect();
    assert_eq!(labels.first().map(String::as_str), Some("3"));
    assert_eq!(
        labels.last().map(String::as_str),
        Some(fmt_exact(many[39]).as_str())
    );
    assert!(labels.len() > 2, "{labels:?}");
    assert_eq!(fmt_exact(1_048_576.0), "1 048 576");
    assert_eq!(fmt_exact(0.25), "0.25");
}

#[test]
fn plots_are_deterministic_svg() {
    let dir = std::env::temp_dir().join(format!("plots_test_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let s = Series {
        name: "lesson".into(),
        points: vec![pt("a", 1.0, 0.0), pt("b", 2.0, 0.5), pt("c", 3.0, 0.2)],
        metric: Metric::Misclassified,
    };
    let (p1, p2) = (dir.join("1.svg"), dir.join("2.svg"));
    error_vs_time(&p1, "t", &s, Some(0.5), 1e-3).unwrap();
    error_vs_time(&p2, "t", &s, Some(0.5), 1e-3).unwrap();
    let (a, b) = (std::fs::read(&p1).unwrap(), std::fs::read(&p2).unwrap());
    assert_eq!(a, b);
    let text = String::from_utf8(a).unwrap();
    assert!(text.contains("no shadows") && text.contains("<text"));
    std::fs::remove_dir_all(&dir).unwrap();
}
