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
fn display(value: f64, text: &[u8], out: &mut Vec<u8>) {
    if as_written(value) {
        out.extend_from_slice(text.strip_suffix(b".0").unwrap_or(text));
    } else {
        display_from_digits(value, text, out);
    }
}

/// The longest text Żmij writes for an `f64` (`-1.2345678901234567e-308`).
const LONGEST: usize = 24;

/// A cell on the stack: the longest text and a separator, rounded up to two 16-byte words
/// (appended whole, then the line cut to its text).
const CELL: usize = 32;

/// [`display`] of `value` followed by `separator`, from Żmij's `text`. The usual value (in
/// [`WITHOUT_EXPONENT`], 26 binary digits or more after the point: no tie, no `.0`;
/// decided from its bits in a few instructions) is laid out in a cell on the stack and
/// appended by fixed-size copies, which compile to a few moves where a copy of any length
/// is a call; the others take [`display`].
#[inline(always)]
pub(super) fn display_then(value: f64, text: &[u8], separator: u8, out: &mut Vec<u8>) {
    if !fraction_of_text(value) {
        display_rare_then(value, text, separator, out);
        return;
    }
    let n = text.len().min(LONGEST);
    let mut cell = [separator; CELL];
    if n >= 16 {
        cell[..16].copy_from_slice(&text[..16]);
        cell[n - 16..n].copy_from_slice(&text[n - 16..n]);
    } else if n >= 8 {
        cell[..8].copy_from_slice(&text[..8]);
        cell[n - 8..n].copy_from_slice(&text[n - 8..n]);
    } else {
        cell[..n].copy_from_slice(&text[..n]);
    }
    let end = out.len() + n + 1;
    out.extend_from_slice(&cell);
    out.truncate(end);
}

/// [`display_then`] of a value it does not lay out itself.
#[inline(never)]
fn display_rare_then(value: f64, text: &[u8], separator: u8, out: &mut Vec<u8>) {
    display(value, text, out);
    out.push(separator);
}

/// Whether Żmij's text of `value` is `Display`'s as it is, by a sufficient test on the bits:
/// a magnitude in [`WITHOUT_EXPONENT`] (one comparison: the bits of finite magnitudes are
/// ordered as their values) whose lowest binary digit is at 2^-26 or below. Such a value is
/// not whole (no `.0` to drop), and its exact expansion, odd × 5^k / 10^k with k ≥ 26, has
/// more than 18 significant digits (5^26 > 1e18), so it is no tie of the shortest digits
/// ([`tie`]).
#[inline(always)]
fn fraction_of_text(value: f64) -> bool {
    const LOW: u64 = WITHOUT_EXPONENT.start.to_bits();
    const HIGH: u64 = WITHOUT_EXPONENT.end.to_bits();
    let bits = value.abs().to_bits();
    let zeros = (bits | (1 << 52)).trailing_zeros() as i32;
    let lowest = (bits >> 52) as i32 - 1075 + zeros;
    bits.wrapping_sub(LOW) < HIGH - LOW && lowest <= -26
}

/// Whether Żmij's text of `value` is `Display`'s but for a trailing `.0`: zero, or a
/// magnitude in [`WITHOUT_EXPONENT`] (one comparison of the bits, which order finite
/// magnitudes as their values) that cannot be a tie ([`tie`]).
#[inline(always)]
fn as_written(value: f64) -> bool {
    const LOW: u64 = WITHOUT_EXPONENT.start.to_bits();
    const HIGH: u64 = WITHOUT_EXPONENT.end.to_bits();
    let bits = value.abs().to_bits();
    (bits.wrapping_sub(LOW) < HIGH - LOW || bits == 0) && tie(value) == Tie::No
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

    /// [`display_then`]'s cell: the value as `Display` prints it, then the separator.
    fn cell(v: f64) -> String {
        let v = v + 0.0;
        let mut out = b"x".to_vec();
        display_then(
            v,
            zmij::Buffer::new().format_finite(v).as_bytes(),
            b';',
            &mut out,
        );
        String::from_utf8(out).unwrap()
    }

    /// The edges of the cell's quick test: the ends of [`WITHOUT_EXPONENT`], the lowest
    /// binary digit at 2^-26 (laid out in the cell) and at 2^-25 (not), whole numbers,
    /// ties, and texts of 1 to 24 bytes.
    #[test]
    fn a_cell_is_the_value_as_display_prints_it_and_its_separator() {
        let at = |odd: f64, lowest: i32| odd * 2f64.powi(lowest);
        for v in [
            0.0,
            -0.0,
            1.0,
            -7.0,
            0.5,
            1e-5,
            1e-5_f64.next_down(),
            1e-5_f64.next_up(),
            -1e-5,
            1e16_f64.next_down(),
            1e16,
            1e-7,
            1.7976931348623157e308,
            5e-324,
            at(1.0, -26),
            at(3.0, -26),
            at(12_345.0, -26),
            at(1.0, -25),
            at(12_345.0, -25),
            at(((1u64 << 53) - 1) as f64, -26),
            at(((1u64 << 53) - 1) as f64, -78),
            -3_369_342_183_012_505.0 / 4.0,
            3085085.0610378026,
            -3_085_085.023_246_659_4,
            0.30000000000000004,
            -1.2345678901234567e-300,
            123.0,
            0.000396,
            0.00039600000000000003,
        ] {
            assert_eq!(cell(v), format!("x{};", v + 0.0), "{v:e}");
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

        /// Any finite `f64` in a cell: as `Display` prints it, then the separator.
        #[test]
        fn a_cell_matches_the_standard_library(bits in any::<u64>()) {
            let v = f64::from_bits(bits);
            prop_assume!(v.is_finite());
            prop_assert_eq!(cell(v), format!("x{};", v + 0.0));
        }

        /// Values with their lowest binary digit near 2^-26 (the quick test's edge), of
        /// every magnitude a CSV has: as `Display` prints them, then the separator.
        #[test]
        fn a_cell_matches_near_its_quick_test(
            odd in 0u64..(1 << 53),
            lowest in -40i32..-10,
            negative in any::<bool>(),
        ) {
            let v = (odd | 1) as f64 * 2f64.powi(lowest);
            let v = if negative { -v } else { v };
            prop_assert_eq!(cell(v), format!("x{};", v + 0.0));
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
