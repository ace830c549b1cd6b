//! The variants over [`crate::taps::OVER`] times their floor or the model,
//! with their reasons ([`crate::why::WHY`]): the list under each lesson's
//! floor tables, and the check that fails the generator when a listed
//! variant has no reason or a reason explains no listed variant.

use anyhow::{bail, Result};

use crate::taps::{over, times, Over};
use crate::why::{
    find, On,
    On::{Gpu, Lavapipe},
    Pass,
    Pass::{Lighting, Map},
    NOT_YET, WHY,
};

/// Fails when a listed variant has no reason, or a reason (for one of its
/// variants) explains no listed variant.
pub fn check(overs: &[Over]) -> Result<()> {
    let mut errors = Vec::new();
    for o in overs {
        if find(&o.lesson, &o.variant, o.pass, o.on).is_none() {
            errors.push(format!(
                "{}'s `{}`, {:?} on {}: {} its {}, and no reason in book/generate/why.rs",
                o.lesson,
                o.variant,
                o.pass,
                o.adapter,
                times(o.ratio),
                what(o.pass)
            ));
        }
    }
    for w in WHY {
        for v in w.variants {
            let listed = overs.iter().any(|o| {
                o.lesson == w.lesson && o.variant == *v && o.pass == w.pass && o.on == w.on
            });
            if !listed {
                errors.push(format!(
                    "why.rs explains {}'s `{v}` ({:?}, {:?}), which is not over {} its {} any more: drop it from the entry",
                    w.lesson,
                    w.pass,
                    w.on,
                    over(),
                    what(w.pass)
                ));
            }
        }
    }
    if !errors.is_empty() {
        bail!(
            "the floor tables' list of variants over their floor or model does not match book/generate/why.rs:\n  {}",
            errors.join("\n  ")
        );
    }
    Ok(())
}

/// What a pass is set against.
fn what(pass: Pass) -> &'static str {
    match pass {
        Lighting => "floor",
        Map => "model",
    }
}

/// The list under a lesson's tables: the variants over, grouped by their
/// pass, their kind of adapter and their reason, each with its ratio on
/// each set; a line saying none is, where none is.
pub fn list(overs: &[Over]) -> String {
    let bound = over();
    if overs.is_empty() {
        return format!(
            "\nNo variant's lit pass is over {bound} its floor, nor its map passes over {bound} the model, on any set.\n"
        );
    }
    // (pass, adapters, the reason's index in WHY or None, variants with
    // their ratios), in the order met.
    type Group<'a> = (Pass, On, Option<usize>, Vec<(&'a str, Vec<&'a Over>)>);
    let mut groups: Vec<Group> = Vec::new();
    for o in overs {
        let reason = WHY.iter().position(|w| {
            w.lesson == o.lesson
                && w.pass == o.pass
                && w.on == o.on
                && w.variants.contains(&o.variant.as_str())
        });
        let at = match groups.iter().position(|g| {
            g.0 == o.pass
                && g.1 == o.on
                && g.2 == reason
                && (reason.is_some() || g.3[0].0 == o.variant)
        }) {
            Some(at) => at,
            None => {
                groups.push((o.pass, o.on, reason, Vec::new()));
                groups.len() - 1
            }
        };
        let variants = &mut groups[at].3;
        match variants.iter_mut().find(|(v, _)| *v == o.variant) {
            Some((_, list)) => list.push(o),
            None => variants.push((&o.variant, vec![o])),
        }
    }
    groups.sort_by_key(|g| (g.0, g.1));
    let mut s = format!(
        "\n**Over {bound} their floor or the model, and why.** Each variant whose lit pass is over {bound} its floor, or whose map passes are over {bound} the model, on a set above, and what it does that its comparisons, or its texels and fragments, do not count:\n\n"
    );
    for (pass, on, reason, variants) in groups {
        let which = match pass {
            Lighting => "Lit pass",
            Map => "Map passes",
        };
        let whose = match on {
            Lavapipe => "on lavapipe",
            Gpu => "on a GPU",
        };
        let named: Vec<String> = variants
            .iter()
            .map(|(v, list)| {
                let ratios: Vec<String> = list
                    .iter()
                    .map(|o| {
                        let ge = if o.at_least { "≥ " } else { "" };
                        match on {
                            Lavapipe => format!("{ge}{}", times(o.ratio)),
                            Gpu => format!("{ge}{} on {}", times(o.ratio), o.adapter),
                        }
                    })
                    .collect();
                format!("`{v}` ({})", ratios.join(", "))
            })
            .collect();
        let why = reason.map_or("**No reason given.**", |i| WHY[i].why);
        s += &format!("- {which} {whose}: {}. {why}\n", named.join(", "));
    }
    let open = NOT_YET.trim_end_matches([':', ' ']);
    if s.contains(NOT_YET) {
        s += &format!(
            "\nA reason that starts \"{open}\" says what was measured; its cause is still open.\n"
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed records and sets, every lesson's variants over.
    fn committed_overs() -> Vec<Over> {
        let (main, sets) = crate::taps::tests::committed();
        let all = crate::taps::adapters(&main, &sets);
        crate::taps::LESSONS
            .iter()
            .flat_map(|l| crate::taps::overs(l, &all))
            .collect()
    }

    #[test]
    fn every_variant_over_its_floor_or_model_says_why() {
        if let Err(e) = check(&committed_overs()) {
            panic!("{e:#}");
        }
    }
}
