//! A technique's knobs: the parameters its chapter discusses (a bias in
//! texels, a kernel's size, a cascade count), on top of its named variants.
//! The window shows them as widgets; `--knob NAME=VALUE` sets them headless.
//! Both go through [`crate::run::instruments::apply_knob`], so a test that sets
//! a knob headless exercises the code a widget calls.

/// What values a knob takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum KnobRange {
    /// A number from `min` to `max`; `log`: the widget's scale is logarithmic.
    Float { min: f64, max: f64, log: bool },
    /// A whole number from `min` to `max`.
    Int { min: i64, max: i64 },
    /// Off (0) or on (1).
    Toggle,
}

/// One knob of a variant, with its current value.
#[derive(Clone, Debug, PartialEq)]
pub struct Knob {
    /// `bias_texels`: what `--knob` and the report call it.
    pub name: &'static str,
    /// One line: what it does, in the chapter's words.
    pub doc: &'static str,
    pub range: KnobRange,
    /// The value the variant runs with now.
    pub value: f64,
}

impl Knob {
    /// Why `value` is not one this knob takes, or `None`.
    pub fn reject(&self, value: f64) -> Option<String> {
        let ok = match self.range {
            KnobRange::Float { min, max, .. } => value.is_finite() && (min..=max).contains(&value),
            KnobRange::Int { min, max } => {
                value.fract() == 0.0 && (min as f64..=max as f64).contains(&value)
            }
            KnobRange::Toggle => value == 0.0 || value == 1.0,
        };
        (!ok).then(|| format!("{} takes {}, not {value}", self.name, self.range_text()))
    }

    /// The range in words: "0 to 64", "whole numbers 1 to 8", "0 or 1".
    pub fn range_text(&self) -> String {
        match self.range {
            KnobRange::Float { min, max, .. } => format!("{min} to {max}"),
            KnobRange::Int { min, max } => format!("whole numbers {min} to {max}"),
            KnobRange::Toggle => "0 (off) or 1 (on)".to_string(),
        }
    }

    /// The value as `--knob` spells it.
    pub fn value_text(&self) -> String {
        match self.range {
            KnobRange::Float { .. } => format!("{}", self.value),
            _ => format!("{}", self.value as i64),
        }
    }
}

/// One `--knob NAME=VALUE`, parsed.
pub fn parse_knob(s: &str) -> Result<(String, f64), String> {
    let (name, value) = s
        .split_once('=')
        .ok_or_else(|| format!("expected NAME=VALUE, got {s:?}"))?;
    let name = name.trim();
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(format!(
            "expected a knob name of letters, digits and _, got {name:?}"
        ));
    }
    let value: f64 = match value.trim() {
        "on" | "true" => 1.0,
        "off" | "false" => 0.0,
        v => v
            .parse()
            .map_err(|_| format!("{name}: expected a number, on or off, got {v:?}"))?,
    };
    Ok((name.to_string(), value))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn knob_lines_parse_and_bad_ones_are_named() {
        assert_eq!(
            parse_knob("bias_texels=1.5"),
            Ok(("bias_texels".into(), 1.5))
        );
        assert_eq!(parse_knob("scissor=off"), Ok(("scissor".into(), 0.0)));
        assert!(parse_knob("bias").unwrap_err().contains("NAME=VALUE"));
        assert!(parse_knob("bias=x").unwrap_err().contains("bias"));
        assert!(parse_knob("b-x=1").is_err());
    }

    #[test]
    fn ranges_reject_what_they_do_not_hold() {
        let k = |range| Knob {
            name: "k",
            doc: "",
            range,
            value: 0.0,
        };
        let f = k(KnobRange::Float {
            min: 0.0,
            max: 4.0,
            log: false,
        });
        assert!(f.reject(4.0).is_none() && f.reject(4.1).is_some());
        assert!(f.reject(f64::NAN).is_some());
        let i = k(KnobRange::Int { min: 1, max: 8 });
        assert!(i.reject(3.0).is_none() && i.reject(2.5).is_some() && i.reject(0.0).is_some());
        let t = k(KnobRange::Toggle);
        assert!(t.reject(1.0).is_none() && t.reject(2.0).is_some());
    }
}
