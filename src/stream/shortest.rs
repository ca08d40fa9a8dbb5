//! The shortest decimal digits that read back to the same `f64` (the Żmij algorithm of the
//! `zmij` crate), laid out as Rust's `Display` lays them out: the CSV's numbers.

/// The shortest decimal digits of a finite `value` (no leading or trailing zeros; `0` has
/// none), the power of ten of the first digit's place plus one, and the sign.
pub(super) struct Shortest {
    digits: [u8; 20],
    len: usize,
    /// The value is `0.d1d2d3… × 10^point`.
    pub(super) point: i32,
    negative: bool,
}

impl Shortest {
    /// The digits of Żmij's text, which is `-`? then either `w.f` (no exponent: `w` is `0`
    /// or has no leading zero, `f` no trailing zero unless it is the `0` of `w.0`) or
    /// `d.ddde±x` / `de±x`: the crate gives its decimal only as text.
    pub(super) fn read(text: &[u8]) -> Self {
        let negative = text.first() == Some(&b'-');
        let body = &text[usize::from(negative)..];
        let (mantissa, exponent) = match body.iter().position(|&b| b == b'e') {
            Some(e) => {
                let (sign, magnitude) = match &body[e + 1..] {
                    [b'-', m @ ..] => (-1, m),
                    [b'+', m @ ..] => (1, m),
                    m => (1, m),
                };
                let x = (magnitude.iter()).fold(0i32, |x, &d| x * 10 + i32::from(d - b'0'));
                (&body[..e], sign * x)
            }
            None => (body, 0),
        };
        let dot = mantissa.iter().position(|&b| b == b'.');
        let (whole, fraction) = match dot {
            Some(dot) => (&mantissa[..dot], &mantissa[dot + 1..]),
            None => (mantissa, &[][..]),
        };
        let mut shortest = Self {
            digits: [0; 20],
            len: 0,
            point: exponent,
            negative,
        };
        if whole == b"0" {
            // 0.000ddd: the zeros after the point move it.
            let zeros = fraction.iter().take_while(|&&b| b == b'0').count();
            let digits = &fraction[zeros..];
            shortest.point -= zeros as i32;
            shortest.len = digits.len().min(20);
            shortest.digits[..shortest.len].copy_from_slice(&digits[..shortest.len]);
        } else {
            let w = whole.len().min(20);
            let f = fraction.len().min(20 - w);
            shortest.point += whole.len() as i32;
            shortest.digits[..w].copy_from_slice(&whole[..w]);
            shortest.digits[w..w + f].copy_from_slice(&fraction[..f]);
            shortest.len = w + f;
        }
        while shortest.len > 0 && shortest.digits[shortest.len - 1] == b'0' {
            shortest.len -= 1;
        }
        if shortest.len == 0 {
            shortest.point = 0;
        }
        shortest
    }

    /// The digits, the first not a zero.
    pub(super) fn digits(&self) -> &[u8] {
        &self.digits[..self.len]
    }
}

/// Whether a finite `value` can lie exactly halfway between two decimals of few
/// significant digits (see [`Tie::is`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Tie {
    /// Its exact decimal expansion does not end in a 5 within 18 significant digits: no
    /// shortest string of 17 or fewer digits is ever a tie.
    No,
    /// Its exact expansion has this many significant digits, the last a 5.
    Digits(usize),
    /// Too large to count exactly in `u128`: treated as a tie.
    Maybe,
}

/// The [`Tie`] class of `value`. Such a value has few binary digits after the point, so its
/// expansion is counted exactly in `u128`; almost every other value is answered in a few
/// instructions from its significand's length and its lowest binary digit's place alone.
#[inline(always)]
pub(super) fn tie(value: f64) -> Tie {
    let bits = value.abs().to_bits();
    // value = odd × 2^lowest, the odd part of 53 − zeros binary digits for a normal value
    // (the implicit bit set at 2^52); a subnormal (exponent field 0, its lowest digit at
    // 2^-1074 or above) and zero land far below the point.
    let zeros = (bits | (1 << 52)).trailing_zeros() as i32;
    let lowest = ((bits >> 52) as i32).max(1) - 1075 + zeros;
    // Below the point the expansion is odd × 5^-lowest (a power of ten shifted), at least
    // 2^((52 − zeros) + (−lowest)·log2 5); from 2^59.8 ≥ 1e18 on that is 19 significant
    // digits or more (log2 5 taken low, log2 1e18 high): never a tie of 17 or fewer.
    if lowest < 0 && (52 - zeros) * 10_000 - lowest * 23_219 >= 597_950 {
        return Tie::No;
    }
    exact_tie(value)
}

/// [`tie`] of a value whose exact expansion may have 18 significant digits or fewer: counted
/// in `u128` (`u64` where it fits).
#[inline(never)]
fn exact_tie(value: f64) -> Tie {
    if value == 0.0 || !value.is_finite() {
        return Tie::No;
    }
    let bits = value.abs().to_bits();
    let (exponent, fraction) = ((bits >> 52) as i32, bits & ((1 << 52) - 1));
    let (mut m, mut e) = if exponent == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1 << 52), exponent - 1075)
    };
    let zeros = m.trailing_zeros();
    m >>= zeros;
    e += zeros as i32;
    let n: u128 = if e >= 0 {
        if e > 74 {
            return Tie::Maybe;
        }
        u128::from(m) << e
    } else if -e > 32 {
        // At least 23 significant digits: never a tie of 17 or fewer.
        return Tie::No;
    } else {
        u128::from(m) * 5u128.pow((-e) as u32)
    };
    let (last, digits) = match u64::try_from(n) {
        Ok(mut n) => {
            while n.is_multiple_of(10) {
                n /= 10;
            }
            (n % 10, n.ilog10())
        }
        Err(_) => {
            let mut n = n;
            while n.is_multiple_of(10) {
                n /= 10;
            }
            ((n % 10) as u64, n.ilog10())
        }
    };
    if last == 5 {
        Tie::Digits(digits as usize + 1)
    } else {
        Tie::No
    }
}

impl Tie {
    /// Whether a value of this class lies exactly halfway between two decimals of `len`
    /// significant digits: its exact decimal expansion has `len + 1` significant digits, the last a 5. There two
    /// shortest strings are equally near, and the standard library and Żmij may pick either
    /// (found by the property test: -842335545753126.25). A value too large to count exactly
    /// is answered "maybe" (true).
    pub(super) fn is(self, len: usize) -> bool {
        match self {
            Tie::No => false,
            Tie::Digits(n) => n == len + 1,
            Tie::Maybe => true,
        }
    }
}

/// Appends `value` as Rust's `Display` prints it (`1`, `0.5`, `0.0000001`, never an
/// exponent), the digits being the shortest that read back to the same number (Żmij's,
/// or the standard library's where it has 17). `-0` is written `0`. `value` must be finite.
pub fn push_display(value: f64, out: &mut Vec<u8>) {
    let value = value + 0.0;
    let mut buffer = zmij::Buffer::new();
    display(value, buffer.format_finite(value).as_bytes(), out);
}

/// The magnitudes Żmij writes without an exponent: those whose shortest decimal `d` has
/// 1e-5 ≤ d < 1e16. Rounding to `f64` is monotone and both ends are the `f64`s nearest
/// them, so for the `value` that `d` reads back to this is 1e-5 ≤ |value| < 1e16.
const WITHOUT_EXPONENT: std::ops::Range<f64> = 1e-5..1e16;

/// [`push_display`] of `value` (not `-0`) from Żmij's `text` of it.
///
/// Żmij prints `1e-5 ≤ |value| < 1e16` (and zero) in the same layout as `Display` but for
/// a trailing `.0` on whole numbers: those bytes are copied as they are when no tie is
/// possible (the usual case, decided from the value in a few instructions); the others are
/// laid out from their digits.
#[inline(always)]
pub(super) fn display(value: f64, text: &[u8], out: &mut Vec<u8>) {
    let magnitude = value.abs();
    if (WITHOUT_EXPONENT.contains(&magnitude) || magnitude == 0.0) && tie(value) == Tie::No {
        out.extend_from_slice(text.strip_suffix(b".0").unwrap_or(text));
    } else {
        display_from_digits(value, text, out);
    }
}

/// [`display`] of a value written with an exponent, or that may be a tie: laid out from
/// Żmij's digits, or printed by the standard library where the two may differ.
#[cold]
#[inline(never)]
fn display_from_digits(value: f64, text: &[u8], out: &mut Vec<u8>) {
    let shortest = Shortest::read(text);
    let (digits, point) = (shortest.digits(), shortest.point);
    if tie(value).is(digits.len()) {
        let _ = std::io::Write::write_fmt(out, format_args!("{value}"));
        return;
    }
    if digits.is_empty() {
        out.push(b'0');
        return;
    }
    if shortest.negative {
        out.push(b'-');
    }
    let n = digits.len() as i32;
    if point <= 0 {
        out.extend_from_slice(b"0.");
        out.resize(out.len() + (-point) as usize, b'0');
        out.extend_from_slice(digits);
    } else if point >= n {
        out.extend_from_slice(digits);
        out.resize(out.len() + (point - n) as usize, b'0');
    } else {
        out.extend_from_slice(&digits[..point as usize]);
        out.push(b'.');
        out.extend_from_slice(&digits[point as usize..]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn display(v: f64) -> String {
        let mut out = Vec::new();
        push_display(v, &mut out);
        String::from_utf8(out).unwrap()
    }

    /// The edges of the layout: integers, exponents far out either way, negative zero.
    #[test]
    fn display_digits_match_the_standard_library_at_the_edges() {
        for v in [
            0.0,
            -0.0,
            1.0,
            -1.5,
            100.0,
            0.1,
            1e-7,
            -2.5e-8,
            123_456_789.125,
            1e15,
            1e16,
            1.7976931348623157e308,
            5e-324,
            f64::MIN_POSITIVE,
            0.30000000000000004,
            // The ends of Żmij's layout without an exponent, and either side of them.
            1e-5,
            1e-5_f64.next_down(),
            1e-5_f64.next_up(),
            -1e-5,
            1e16_f64.next_down(),
            1e16_f64.next_up(),
            // Ties of the shortest digits (the standard library decides them), short binary
            // fractions, and values of a CSV's magnitudes above 2^20.
            -3_369_342_183_012_505.0 / 4.0, // -842335545753126.25, exactly
            0.5,
            180.0,
            3085085.0610378026,
            -3_085_085.023_246_659_4,
        ] {
            assert_eq!(display(v), (v + 0.0).to_string(), "{v:e}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]
        /// Any finite `f64` prints as `Display` prints it: same shortest digits, same layout.
        #[test]
        fn display_digits_match_the_standard_library(bits in any::<u64>()) {
            let v = f64::from_bits(bits);
            prop_assume!(v.is_finite());
            prop_assert_eq!(display(v), (v + 0.0).to_string());
        }

        /// Values with few binary digits after the point (odd × 2^-k), where the shortest
        /// digits may be a tie and [`tie`] must count exactly, and whole numbers: as `Display`
        /// prints them.
        #[test]
        fn display_digits_match_for_short_binary_fractions(
            odd in 0u64..(1 << 53),
            k in -80i32..60,
            negative in any::<bool>(),
        ) {
            let v = (odd | 1) as f64 * 2f64.powi(-k);
            let v = if negative { -v } else { v };
            prop_assume!(v.is_finite());
            prop_assert_eq!(display(v), (v + 0.0).to_string());
        }
    }
}
