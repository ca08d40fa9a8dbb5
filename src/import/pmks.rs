//! PMKS's text format (as PMKS's `ConvertTextToData` reads it): one joint a line,
//!
//! ```text
//! ground,input,R,0,0,tfft
//! input,coupler,R,0,50,tfff
//! coupler,slider,R,120,370,tfff
//! slider,ground,P,120,300,0,tfff
//! ```
//!
//! Words are separated by commas or spaces. The last word that is a joint type (`R`, `P`,
//! `RP`, `G`) is the type; the words before it are the links; then x, y, an optional angle
//! (degrees: the slide direction of a `P` joint), and optional flags (`t`/`f`, or `+`/`-`
//! in older files) whose fourth marks the driving input. A line `mech=` (PMKS's section
//! header) may precede the joints; other lines holding `=` (PMKS's settings) are skipped.

use crate::error::Result;
use crate::scene::Source;

use super::linkage::{Joint, JointKind, Linkage, error};

/// Reads PMKS text.
///
/// # Errors
/// [`crate::Error::Import`] naming the line and word that is wrong: a line without a joint
/// type or links, coordinates that are not numbers, an `RP` or `G` joint, two driving
/// inputs.
pub fn parse(source: &Source) -> Result<Linkage> {
    let text = &source.text;
    let mut joints = Vec::new();
    let mut drive = None;
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let mut body = line.trim_end_matches(['\n', '\r']);
        let mut body_start = start;
        if let Some(rest) = body.trim_start().strip_prefix("mech=") {
            body_start = start + (body.len() - rest.len());
            body = rest;
        } else if body.contains('=') {
            continue;
        }
        // Words with their spans.
        let mut words: Vec<(&str, std::ops::Range<usize>)> = Vec::new();
        let mut i = 0;
        for piece in body.split([',', ' ', '\t']) {
            if !piece.is_empty() {
                words.push((piece, body_start + i..body_start + i + piece.len()));
            }
            i += piece.len() + 1;
        }
        if words.is_empty() {
            continue;
        }
        let line_span = words[0].1.start..words[words.len() - 1].1.end;
        let is_type = |w: &str| matches!(w.to_ascii_uppercase().as_str(), "R" | "P" | "RP" | "G");
        let Some(t) = words.iter().rposition(|(w, _)| is_type(w)) else {
            return Err(error(
                source,
                line_span,
                "no joint type on this line; a PMKS joint is `link1,link2,R,x,y` (types R, P, RP, \
                 G)",
            ));
        };
        if t == 0 {
            return Err(error(
                source,
                words[0].1.clone(),
                "the joint names no link before its type; write `ground,input,R,0,0`",
            ));
        }
        let number = |k: usize, what: &str| -> Result<f64> {
            let (w, span) = words.get(k).ok_or_else(|| {
                error(
                    source,
                    line_span.clone(),
                    format!("the joint has no {what}; write `links,type,x,y`"),
                )
            })?;
            w.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    error(
                        source,
                        span.clone(),
                        format!("{what}: `{w}` is not a number"),
                    )
                })
        };
        let at = [
            number(t + 1, "x coordinate")?,
            number(t + 2, "y coordinate")?,
        ];
        let mut k = t + 3;
        let angle = match words.get(k) {
            Some((w, _)) if w.parse::<f64>().is_ok() => {
                k += 1;
                Some(number(k - 1, "angle")?)
            }
            _ => None,
        };
        if let Some((flags, span)) = words.get(k) {
            let driving = flags.chars().nth(3).is_some_and(|c| c == 't' || c == '+');
            if driving {
                if drive.is_some() {
                    return Err(error(
                        source,
                        span.clone(),
                        "a second driving input; mechdiff drives one joint: mark one with `t` \
                         in the fourth flag",
                    ));
                }
                drive = Some(joints.len());
            }
        }
        let type_span = words[t].1.clone();
        let kind = match words[t].0.to_ascii_uppercase().as_str() {
            "R" => JointKind::Revolute,
            "P" => JointKind::Prismatic {
                angle: angle.unwrap_or(0.0),
            },
            other => {
                return Err(error(
                    source,
                    type_span,
                    format!(
                        "a `{other}` joint is not imported yet (R and P are); write it in the \
                         scene as a `pin_in_slot` or `gear` joint (docs/scene-format.md)"
                    ),
                ));
            }
        };
        let links = words[..t]
            .iter()
            .map(|(w, _)| {
                if w.eq_ignore_ascii_case("ground") {
                    "ground".to_owned()
                } else {
                    (*w).to_owned()
                }
            })
            .collect();
        joints.push(Joint {
            kind,
            links,
            at,
            span: line_span,
        });
    }
    Ok(Linkage {
        format: "PMKS text",
        joints,
        drive,
    })
}
