//! Label placement in pixel space: each point's label beside its marker,
//! or, where points crowd, in a column with leader lines.

use super::draw::Rect;
use super::{max_of, min_of};

/// Within this distance (px) of each other, points whose labels cannot
/// touch them unambiguously are labelled together in one column.
const CROWD_PX: f64 = 36.0;
/// A touching label's gap to its marker's centre, px.
const TOUCH_PX: f64 = 9.0;

/// The distance from `p` to the nearest point of `r`.
fn rect_dist(r: &Rect, p: (f64, f64)) -> f64 {
    let n = r.nearest(p);
    (n.0 - p.0).hypot(n.1 - p.1)
}

/// Places the labels of the points `order` (indices into `pts`, in order of
/// priority; `widths[k]` and `h` the label sizes) in `plot`, around
/// `obstacles`. Each label either touches its own point, nearer to it than to
/// any other point of `pts` by a clear margin, or, where points crowd, goes
/// in a column beside its group, joined to its point by a leader line
/// ending at the returned point. Returns (index, label box, leader end).
pub(super) fn place_labels(
    pts: &[(f64, f64)],
    order: &[usize],
    widths: &[f64],
    h: f64,
    plot: Rect,
    obstacles: &[Rect],
) -> Vec<Label> {
    let close = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1) <= CROWD_PX;
    // Points that cannot have a touching label, and their labelled
    // neighbours, go to columns; repeat until the rest all touch.
    let mut crowded = vec![false; pts.len()];
    let (mut out, mut obs) = loop {
        let mut obs = obstacles.to_vec();
        let mut out = Vec::new();
        let mut failed = Vec::new();
        for &k in order.iter().filter(|&&k| !crowded[k]) {
            match touching_spot(pts, k, widths[k], h, plot, &obs) {
                Some(r) => {
                    obs.push(r);
                    out.push((k, r, None));
                }
                None => failed.push(k),
            }
        }
        if failed.is_empty() {
            break (out, obs);
        }
        for f in failed {
            for &j in order {
                if j == f || close(pts[j], pts[f]) {
                    crowded[j] = true;
                }
            }
        }
    };
    // The crowded points in groups (linked within CROWD_PX), in order of
    // their first member.
    let mut group_of: Vec<Option<usize>> = vec![None; pts.len()];
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for &k in order.iter().filter(|&&k| crowded[k]) {
        if group_of[k].is_some() {
            continue;
        }
        let g = groups.len();
        let mut members = vec![k];
        group_of[k] = Some(g);
        let mut i = 0;
        while i < members.len() {
            let m = members[i];
            for &j in order {
                if crowded[j] && group_of[j].is_none() && close(pts[j], pts[m]) {
                    group_of[j] = Some(g);
                    members.push(j);
                }
            }
            i += 1;
        }
        groups.push(members);
    }
    for g in groups {
        let labels: Vec<Rect> = out.iter().map(|o| o.1).collect();
        let column = place_column(pts, &g, widths, h, plot, &obs, &labels);
        for &(k, r, end) in &column {
            obs.push(r);
            out.push((k, r, Some(end)));
        }
    }
    out
}

/// A spot for point `k`'s label right beside its marker: in the plot, clear
/// of the obstacles, and nearer to point `k` than to any other point by at
/// least 5 px; the first such of eight spots around the marker, if any.
fn touching_spot(
    pts: &[(f64, f64)],
    k: usize,
    w: f64,
    h: f64,
    plot: Rect,
    obstacles: &[Rect],
) -> Option<Rect> {
    let c = pts[k];
    let d = TOUCH_PX;
    let diag = d * 0.75;
    let spots = [
        (c.0 + d, c.1 - h / 2.0),
        (c.0 - d - w, c.1 - h / 2.0),
        (c.0 + diag, c.1 - diag - h),
        (c.0 + diag, c.1 + diag),
        (c.0 - diag - w, c.1 - diag - h),
        (c.0 - diag - w, c.1 + diag),
        (c.0 - w / 2.0, c.1 - d - h),
        (c.0 - w / 2.0, c.1 + d),
    ];
    spots.iter().map(|&(x, y)| Rect::new(x, y, w, h)).find(|r| {
        let own = rect_dist(r, c);
        r.outside(&plot) == 0.0
            && obstacles.iter().all(|o| r.overlap(o) == 0.0)
            && pts
                .iter()
                .enumerate()
                .all(|(j, &q)| j == k || rect_dist(r, q) >= own + 5.0)
    })
}

/// The distance from `p` to the segment a-b.
fn seg_dist(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a.0 + t * dx - p.0).hypot(a.1 + t * dy - p.1)
}

/// Whether the segment a-b meets the rectangle `r`.
fn seg_hits(a: (f64, f64), b: (f64, f64), r: &Rect) -> bool {
    if r.contains(a) || r.contains(b) {
        return true;
    }
    let corners = [(r.x0, r.y0), (r.x1, r.y0), (r.x1, r.y1), (r.x0, r.y1)];
    (0..4).any(|i| crosses(a, b, corners[i], corners[(i + 1) % 4]))
}

/// A placed label: the point's index, the label box and, where it has one,
/// its leader's end.
type Label = (usize, Rect, Option<(f64, f64)>);

/// A column label: the point's index, the label box and its leader's end.
type Placed = (usize, Rect, (f64, f64));

/// Whether the segments a-b and c-d cross.
fn crosses(a: (f64, f64), b: (f64, f64), c: (f64, f64), d: (f64, f64)) -> bool {
    let side = |p: (f64, f64), q: (f64, f64), r: (f64, f64)| {
        (q.0 - p.0) * (r.1 - p.1) - (q.1 - p.1) * (r.0 - p.0)
    };
    let (d1, d2) = (side(c, d, a), side(c, d, b));
    let (d3, d4) = (side(a, b, c), side(a, b, d));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// The labels of `group` stacked in a column right or left of it, the
/// column's side, offset and the rows' order chosen to overlap the least of
/// the obstacles (and stay in the plot), then for the shortest leader lines
/// with the fewest crossings. Returns (index, label box, leader end).
fn place_column(
    pts: &[(f64, f64)],
    group: &[usize],
    widths: &[f64],
    h: f64,
    plot: Rect,
    obstacles: &[Rect],
    labels: &[Rect],
) -> Vec<Placed> {
    let row = h + 3.0;
    let n = group.len();
    let col_h = row * n as f64 - 3.0;
    let col_w = group.iter().map(|&k| widths[k]).fold(0.0, f64::max);
    let xs = || group.iter().map(|&k| pts[k].0);
    let ys = || group.iter().map(|&k| pts[k].1);
    let (gx0, gx1) = (min_of(xs()), max_of(xs()));
    let (gy0, gy1) = (min_of(ys()), max_of(ys()));
    let cy = (gy0 + gy1) / 2.0;
    // Row k's box and its leader end, for a column at x0 (its left edge)
    // and top y0.
    let layout = |right: bool, x0: f64, y0: f64, rows: &[usize]| -> Vec<Placed> {
        rows.iter()
            .enumerate()
            .map(|(i, &k)| {
                let y = y0 + row * i as f64;
                let (r, end) = if right {
                    let r = Rect::new(x0, y, widths[k], h);
                    (r, (r.x0 - 2.0, y + h / 2.0))
                } else {
                    let r = Rect::new(x0 + col_w - widths[k], y, widths[k], h);
                    (r, (r.x1 + 2.0, y + h / 2.0))
                };
                (k, r, end)
            })
            .collect()
    };
    // Leader crossings, then total length, of an arrangement.
    let score = |rows: &[Placed]| -> (usize, f64) {
        let mut crossings = 0;
        for i in 0..rows.len() {
            for j in i + 1..rows.len() {
                if crosses(pts[rows[i].0], rows[i].2, pts[rows[j].0], rows[j].2) {
                    crossings += 1;
                }
            }
        }
        let len = rows
            .iter()
            .map(|&(k, _, e)| (e.0 - pts[k].0).hypot(e.1 - pts[k].1))
            .sum();
        (crossings, len)
    };
    let others: Vec<(f64, f64)> = (0..pts.len())
        .filter(|j| !group.contains(j))
        .map(|j| pts[j])
        .collect();
    let mut best: Option<((f64, usize, f64), Vec<Placed>)> = None;
    for right in [true, false] {
        for gap in [18.0, 34.0, 56.0, 84.0, 120.0, 170.0] {
            let x0 = if right { gx1 + gap } else { gx0 - gap - col_w };
            for s in 0..=30 {
                // 0, -1, +1, -2, +2, ... rows up or down.
                let shift = if s % 2 == 1 { -((s + 1) / 2) } else { s / 2 } as f64;
                let y0 = cy - col_h / 2.0 + shift * row;
                // The rows' order: by height, then improved by swapping
                // neighbours while that removes crossings or shortens leaders.
                let mut rows: Vec<usize> = group.to_vec();
                rows.sort_by(|&a, &b| {
                    pts[a]
                        .1
                        .total_cmp(&pts[b].1)
                        .then(pts[a].0.total_cmp(&pts[b].0))
                        .then(a.cmp(&b))
                });
                for _ in 0..n * n {
                    let mut improved = false;
                    for i in 0..n.saturating_sub(1) {
                        let now = score(&layout(right, x0, y0, &rows));
                        rows.swap(i, i + 1);
                        let then = score(&layout(right, x0, y0, &rows));
                        if then.0 < now.0 || (then.0 == now.0 && then.1 < now.1 - 1e-9) {
                            improved = true;
                        } else {
                            rows.swap(i, i + 1);
                        }
                    }
                    if !improved {
                        break;
                    }
                }
                let placed = layout(right, x0, y0, &rows);
                let mut cost = 0.0;
                for (_, r, _) in &placed {
                    cost += 1e3 * r.outside(&plot);
                    cost += obstacles.iter().map(|o| r.overlap(o)).sum::<f64>();
                    // A label beside another point would read as its label.
                    let near = others.iter().filter(|&&q| rect_dist(r, q) < 10.0).count();
                    cost += 200.0 * near as f64;
                }
                // A leader over another point or through a label misleads.
                for &(k, _, e) in &placed {
                    let a = pts[k];
                    let hits = (0..pts.len())
                        .filter(|&j| j != k && seg_dist(a, e, pts[j]) < 7.0)
                        .count()
                        + labels
                            .iter()
                            .filter(|r| seg_hits(a, e, &r.grow(1.0)))
                            .count();
                    cost += 300.0 * hits as f64;
                }
                let (crossings, len) = score(&placed);
                let key = (cost, crossings, len);
                let better = match &best {
                    None => true,
                    Some((b, _)) => {
                        key.0 < b.0
                            || (key.0 == b.0 && (key.1 < b.1 || (key.1 == b.1 && key.2 < b.2)))
                    }
                };
                if better {
                    best = Some((key, placed));
                }
            }
        }
    }
    best.map(|b| b.1).unwrap_or_default()
}
