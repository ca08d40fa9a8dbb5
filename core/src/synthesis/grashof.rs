//! Grashof's classes of a four-bar loop: which of its links turn fully.
//!
//! With s the shortest and l the longest of the four links (ground |O4 − O2|, crank,
//! coupler, rocker) and p, q the other two, the loop is a Grashof linkage when
//! s + l < p + q: then the shortest link turns fully against the other three, and which
//! link is shortest names the class (Norton, *Design of Machinery*, §2.12). Otherwise
//! (s + l ≥ p + q, the change-point case s + l = p + q included) no link turns fully
//! against the ground and the loop is a triple rocker.
//!
//! | class | condition |
//! |---|---|
//! | [`GrashofClass::CrankRocker`] | Grashof, the crank shortest: the crank turns, the rocker rocks |
//! | [`GrashofClass::DoubleCrank`] | Grashof, the ground shortest: crank and rocker both turn (drag link) |
//! | [`GrashofClass::RockerCrank`] | Grashof, the rocker shortest: the rocker turns, the crank rocks |
//! | [`GrashofClass::DoubleRocker`] | Grashof, the coupler shortest: the coupler turns, crank and rocker rock |
//! | [`GrashofClass::TripleRocker`] | not Grashof |
//!
//! ```
//! use mechdiff_core::synthesis::GrashofClass;
//! // ground 1, crank 0.3, coupler 1.1, rocker 0.9: 0.3 + 1.1 < 1 + 0.9.
//! assert_eq!(GrashofClass::of(1.0, 0.3, 1.1, 0.9), GrashofClass::CrankRocker);
//! assert_eq!(GrashofClass::of(0.3, 1.0, 1.1, 0.9), GrashofClass::DoubleCrank);
//! assert_eq!(GrashofClass::of(1.0, 0.8, 0.5, 1.6), GrashofClass::TripleRocker);
//! assert_eq!(GrashofClass::named("rocker-crank"), Some(GrashofClass::RockerCrank));
//! ```

/// A four-bar loop's Grashof class, or [`GrashofClass::Any`] as a constraint that asks none.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub enum GrashofClass {
    /// No class required (a constraint only; [`GrashofClass::of`] never gives it).
    #[default]
    Any,
    /// Grashof, the crank shortest.
    CrankRocker,
    /// Grashof, the ground shortest.
    DoubleCrank,
    /// Grashof, the rocker shortest.
    RockerCrank,
    /// Grashof, the coupler shortest.
    DoubleRocker,
    /// Not Grashof: s + l ≥ p + q.
    TripleRocker,
}

impl GrashofClass {
    /// Every class by the name a scene writes, in order.
    pub const NAMES: [(&'static str, GrashofClass); 6] = [
        ("any", GrashofClass::Any),
        ("crank-rocker", GrashofClass::CrankRocker),
        ("double-crank", GrashofClass::DoubleCrank),
        ("rocker-crank", GrashofClass::RockerCrank),
        ("double-rocker", GrashofClass::DoubleRocker),
        ("triple-rocker", GrashofClass::TripleRocker),
    ];

    /// The class a scene names `name`, if any.
    pub fn named(name: &str) -> Option<GrashofClass> {
        Self::NAMES.iter().find(|(n, _)| *n == name).map(|c| c.1)
    }

    /// The name a scene writes.
    pub fn name(self) -> &'static str {
        Self::NAMES
            .iter()
            .find(|(_, c)| *c == self)
            .map_or("any", |c| c.0)
    }

    /// The class of the loop with these link lengths (never [`GrashofClass::Any`]).
    pub fn of(ground: f64, crank: f64, coupler: f64, rocker: f64) -> GrashofClass {
        let links = [ground, crank, coupler, rocker];
        let shortest = links.iter().copied().fold(f64::INFINITY, f64::min);
        let longest = links.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let others = links.iter().sum::<f64>() - shortest - longest;
        // Not `>=`: NaN lengths are no Grashof linkage either.
        if (shortest + longest).partial_cmp(&others) != Some(std::cmp::Ordering::Less) {
            return GrashofClass::TripleRocker;
        }
        // Strictly Grashof: the shortest link is unique (a tie s = s' would need l < q).
        if crank == shortest {
            GrashofClass::CrankRocker
        } else if ground == shortest {
            GrashofClass::DoubleCrank
        } else if rocker == shortest {
            GrashofClass::RockerCrank
        } else {
            GrashofClass::DoubleRocker
        }
    }

    /// Grashof's margin p + q − s − l of the loop (> 0: Grashof).
    pub fn margin(ground: f64, crank: f64, coupler: f64, rocker: f64) -> f64 {
        let mut links = [ground, crank, coupler, rocker];
        links.sort_by(f64::total_cmp);
        links[1] + links[2] - links[0] - links[3]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_shortest_link_names_its_class_and_names_read_back() {
        // Lengths 1, 2, 3, 3.5: 1 + 3.5 < 2 + 3, Grashof; the shortest link at each place.
        let (s, a, b, l) = (1.0, 2.0, 3.0, 3.5);
        assert_eq!(GrashofClass::of(a, s, b, l), GrashofClass::CrankRocker);
        assert_eq!(GrashofClass::of(s, a, b, l), GrashofClass::DoubleCrank);
        assert_eq!(GrashofClass::of(a, b, l, s), GrashofClass::RockerCrank);
        assert_eq!(GrashofClass::of(a, b, s, l), GrashofClass::DoubleRocker);
        // s + l = p + q (change point) and s + l > p + q are not Grashof.
        assert_eq!(
            GrashofClass::of(1.0, 2.0, 3.0, 4.0),
            GrashofClass::TripleRocker
        );
        assert_eq!(
            GrashofClass::of(1.0, 2.0, 3.0, 4.5),
            GrashofClass::TripleRocker
        );
        assert_eq!(
            GrashofClass::of(f64::NAN, 1.0, 1.0, 1.0),
            GrashofClass::TripleRocker
        );
        for (name, class) in GrashofClass::NAMES {
            assert_eq!(GrashofClass::named(name), Some(class));
            assert_eq!(class.name(), name);
        }
        assert_eq!(GrashofClass::named("crank_rocker"), None);
    }
}
