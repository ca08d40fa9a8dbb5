//! Which closed form fits a loop: matched from the joints (terms) of its rows.

use super::pattern::{Angle, End, Hinge, Pattern, Shift, sub};
use crate::geometry::branch::Loop;
use crate::geometry::constraints::{Body, Equations, Term, cross};

/// Matches loop `l` of `eq` against the patterns (without its branch).
pub(super) fn pattern(eq: &Equations, l: &Loop) -> Option<(usize, Pattern)> {
    let k = l.columns.first()? / 3;
    if l.columns.len() == 6 {
        return dyad(eq, l);
    }
    if l.columns.len() != 3 || l.columns.iter().any(|&c| c / 3 != k) {
        return None;
    }
    let me = Some(k);
    let mut terms: Vec<Term> = Vec::with_capacity(2);
    for &r in &l.rows {
        let t = eq.terms[eq.row_joint[r]];
        if !terms.contains(&t) {
            terms.push(t);
        }
    }
    if terms.len() != 2 {
        return None;
    }
    let other = |i: usize| terms[1 - i];
    for (i, t) in terms.iter().enumerate() {
        match *t {
            Term::Revolute { a, pa, b, pb } if a != b && (a == me || b == me) => {
                let hinge = Hinge::seen_from(me, (a, pa), (b, pb));
                let angle = match other(i) {
                    Term::DriveAngle { a, b, phi0 } if a != b && b == me => Angle::Driven {
                        other: a,
                        sign: 1.0,
                        phi0,
                    },
                    Term::DriveAngle { a, b, phi0 } if a != b && a == me => Angle::Driven {
                        other: b,
                        sign: -1.0,
                        phi0,
                    },
                    Term::PinInSlot { line, pin, p } if line.body == me && pin != me => {
                        Angle::SlotThroughPin {
                            direction: line.direction,
                            c: cross(line.direction, sub(line.origin, hinge.at_body)),
                            pin,
                            at: p,
                        }
                    }
                    Term::PinInSlot { line, pin, p } if pin == me && line.body != me => {
                        Angle::PinInKnownSlot {
                            line,
                            r: sub(p, hinge.at_body),
                        }
                    }
                    Term::RackPinion {
                        a,
                        b,
                        slide,
                        s0,
                        radius,
                    } if (a == me) != (b == me)
                        && ![slide.slider, slide.line.body].contains(&me) =>
                    {
                        let (other, sign) = if b == me { (a, 1.0) } else { (b, -1.0) };
                        Angle::Rolling {
                            other,
                            sign,
                            slide,
                            s0,
                            radius,
                        }
                    }
                    Term::Gear {
                        a1,
                        b1,
                        a2,
                        b2,
                        ratio,
                    } => geared(me, [(b2, 1.0), (a2, -1.0), (b1, -ratio), (a1, ratio)])?,
                    _ => return None,
                };
                let pattern = Pattern::Hinged {
                    hinge,
                    angle,
                    rider: None,
                };
                return Some((k, pattern));
            }
            Term::Prismatic { slide, offset } if slide.slider == me && slide.line.body != me => {
                let shift = match other(i) {
                    Term::DriveSlide { slide: s, s0, phi0 } if s == slide => {
                        Shift::Driven { s0, phi0 }
                    }
                    Term::PinInSlot { line, pin, p } if line.body == me && pin != me => {
                        Shift::SlotThroughPin { line, pin, at: p }
                    }
                    Term::PinInSlot { line, pin, p } if pin == me && line.body != me => {
                        Shift::PinInKnownSlot { line, p }
                    }
                    Term::RackPinion {
                        a,
                        b,
                        slide: s,
                        s0,
                        radius,
                    } if s == slide && a != me && b != me => Shift::Rolling { a, b, s0, radius },
                    _ => return None,
                };
                return Some((
                    k,
                    Pattern::Sliding {
                        slide,
                        offset,
                        shift,
                    },
                ));
            }
            _ => {}
        }
    }
    None
}

/// The angle of `me` from the gear condition `Σ cᵢ θᵢ = 0`: `θ = Σ kᵢ θᵢ` over the other
/// links, or `None` if the condition does not involve `me` (or only through the ground).
fn geared(me: Body, condition: [(Body, f64); 4]) -> Option<Angle> {
    let own: f64 = condition
        .iter()
        .filter(|(b, _)| *b == me)
        .map(|(_, c)| c)
        .sum();
    if me.is_none() || own == 0.0 {
        return None;
    }
    let terms = condition.map(|(b, c)| if b == me { (None, 0.0) } else { (b, -c / own) });
    Some(Angle::Geared { terms })
}

/// Matches a two-link loop: RRR, RRP or RPR dyad.
fn dyad(eq: &Equations, l: &Loop) -> Option<(usize, Pattern)> {
    let mut bodies: Vec<usize> = l.columns.iter().map(|&c| c / 3).collect();
    bodies.sort_unstable();
    bodies.dedup();
    let [k1, k2] = bodies[..] else { return None };
    let mut terms: Vec<Term> = Vec::with_capacity(3);
    for &r in &l.rows {
        let t = eq.terms[eq.row_joint[r]];
        if !terms.contains(&t) {
            terms.push(t);
        }
    }
    if terms.len() != 3 {
        return None;
    }
    let (b1, b2) = (Some(k1), Some(k2));
    if let Some(found) = sliding_pair(&terms, [b1, b2]) {
        return Some(found);
    }
    let unknown = |b: Body| b == b1 || b == b2;
    let mut joint = None;
    let mut ends: [Option<End>; 2] = [None, None];
    for t in &terms {
        match *t {
            Term::Revolute { a, pa, b, pb } if a == b1 && b == b2 => joint = Some([pa, pb]),
            Term::Revolute { a, pa, b, pb } if a == b2 && b == b1 => joint = Some([pb, pa]),
            Term::Revolute { a, pa, b, pb } if unknown(a) != unknown(b) => {
                let me = if unknown(b) { b } else { a };
                let hinge = Hinge::seen_from(me, (a, pa), (b, pb));
                ends[usize::from(me == b2)] = Some(End::Hinge(hinge));
            }
            Term::Prismatic { slide, offset }
                if unknown(slide.slider) && !unknown(slide.line.body) =>
            {
                ends[usize::from(slide.slider == b2)] = Some(End::Slide { slide, offset });
            }
            _ => return None,
        }
    }
    let joint = joint?;
    match ends {
        [Some(End::Hinge(hinge)), Some(end)] => Some((
            k1,
            Pattern::Dyad {
                hinge,
                joint,
                second: k2,
                end,
            },
        )),
        [Some(end), Some(End::Hinge(hinge))] => Some((
            k2,
            Pattern::Dyad {
                hinge,
                joint: [joint[1], joint[0]],
                second: k1,
                end,
            },
        )),
        _ => None,
    }
}

/// The RPR dyad: two links, each hinged to a known link, joined by a prismatic pair (so they
/// turn together). The link carrying the line turns like a slotted rocker whose line passes
/// through the other's hinge `K_S`: with `A` their common rotation,
/// `cross(A d, K_S − K_L) = e − cross(d, p − h_S − o + h_L)` (`d`, `o` the line, `e` its
/// offset, `p` the slider's point, `h` the hinges' local points); the other link then
/// follows at its hinge.
fn sliding_pair(terms: &[Term], unknown: [Body; 2]) -> Option<(usize, Pattern)> {
    let mut hinges: Vec<(Body, Hinge)> = Vec::with_capacity(2);
    let mut slide = None;
    for t in terms {
        match *t {
            Term::Revolute { a, pa, b, pb } if unknown.contains(&a) != unknown.contains(&b) => {
                let me = if unknown.contains(&b) { b } else { a };
                hinges.push((me, Hinge::seen_from(me, (a, pa), (b, pb))));
            }
            Term::Prismatic { slide: s, offset }
                if s.line.body != s.slider
                    && unknown.contains(&s.line.body)
                    && unknown.contains(&s.slider) =>
            {
                slide = Some((s, offset));
            }
            _ => return None,
        }
    }
    let (slide, offset) = slide?;
    let hinge_of = |link: Body| hinges.iter().find(|(me, _)| *me == link).map(|&(_, h)| h);
    let (hl, hs) = (hinge_of(slide.line.body)?, hinge_of(slide.slider)?);
    let (d, o) = (slide.line.direction, slide.line.origin);
    let c = offset + cross(d, sub(o, hl.at_body)) - cross(d, sub(slide.point, hs.at_body));
    Some((
        slide.line.body?,
        Pattern::Hinged {
            hinge: hl,
            angle: Angle::SlotThroughPin {
                direction: d,
                c,
                pin: hs.known,
                at: hs.at_known,
            },
            rider: Some((slide.slider?, hs)),
        },
    ))
}
