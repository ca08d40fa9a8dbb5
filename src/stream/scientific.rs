//! Numbers in scientific notation with [`DIGITS`] significant digits, correctly rounded, as
//! `format!("{:.8e}")` prints them: the streamed table's fixed-width cells and the cells of
//! a table column too wide for fixed point.

use super::shortest::{Shortest, tie};

/// Significant digits of a column's largest value in the printed table (the CSV carries every
/// digit).
pub const DIGITS: i32 = 9;

/// The width of a number in the streamed table: `-d.dddddddde-308`, the longest an `f64`
/// prints in scientific notation with [`DIGITS`] significant digits.
pub const SCIENTIFIC_WIDTH: usize = DIGITS as usize + 7;

/// Appends finite `value` as `format!("{:.8e}", value + 0.0)` prints it ([`DIGITS`]
/// significant digits, correctly rounded), right-aligned in `width`.
pub fn push_scientific(value: f64, width: usize, out: &mut Vec<u8>) {
    scientific(value + 0.0, width, out);
}

/// Appends finite `value` as `format!("{value:.8e}")` prints it ([`DIGITS`] significant
/// digits, correctly rounded; `-0` keeps its sign), with no padding: a cell of the table
/// printed from its values.
pub fn push_scientific_signed(value: f64, out: &mut Vec<u8>) {
    scientific(value, 0, out);
}

/// The significant digits kept in the streamed table.
const KEPT: usize = DIGITS as usize;

/// Powers of ten exact in `f64`.
const POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// The longest scientific cell: `-d.dddddddde-308`.
const CELL: usize = SCIENTIFIC_WIDTH;

/// The two-digit numbers `00` to `99`, one after the other.
const PAIRS: [u8; 200] = {
    let mut pairs = [0; 200];
    let mut k = 0;
    while k < 100 {
        pairs[2 * k] = b'0' + (k / 10) as u8;
        pairs[2 * k + 1] = b'0' + (k % 10) as u8;
        k += 1;
    }
    pairs
};

/// [`push_scientific`] of `value` (not `-0`).
///
/// Most values take [`nine_digits`]; the others (beyond 1e±14…1e31, or within 1e-6
/// of a rounding tie) round Żmij's shortest digits ([`nine_of_shortest`]) or, where that
/// cannot decide, let the standard library print them. The cell is laid out right-aligned in
/// a [`CELL`]-byte block and appended in one copy.
#[inline]
pub(super) fn scientific(value: f64, width: usize, out: &mut Vec<u8>) {
    let (mantissa, exponent) = match nine_digits(value) {
        Some((n, k)) => (with_point(n), k),
        None => match rare_mantissa(value) {
            Some(found) => found,
            None => {
                let _ =
                    std::io::Write::write_fmt(out, format_args!("{:>width$.*e}", KEPT - 1, value));
                return;
            }
        },
    };
    let mut cell = [b' '; CELL];
    // The exponent's digits (no leading zero), its sign and the `e`, from the end.
    let magnitude = exponent.unsigned_abs() as usize;
    let mut start = CELL - 2;
    cell[start..].copy_from_slice(&PAIRS[2 * (magnitude % 100)..][..2]);
    if magnitude >= 100 {
        start -= 1;
        cell[start] = b'0' + (magnitude / 100) as u8;
    } else if magnitude < 10 {
        start += 1;
    }
    if exponent < 0 {
        start -= 1;
        cell[start] = b'-';
    }
    start -= 1;
    cell[start] = b'e';
    // `d.dddddddd`, and the sign.
    start -= KEPT + 1;
    cell[start..start + KEPT + 1].copy_from_slice(&mantissa);
    if value.is_sign_negative() {
        start -= 1;
        cell[start] = b'-';
    }
    if width > CELL {
        out.resize(out.len() + (width - CELL), b' ');
    }
    if width >= CELL {
        out.extend_from_slice(&cell);
    } else {
        out.extend_from_slice(&cell[start.min(CELL - width)..]);
    }
}

/// `d.dddddddd`: the [`KEPT`] digits of `n` (10^8 ≤ n < 10^9, or 0), a point after the first;
/// the other eight made two at a time.
#[inline]
fn with_point(n: u32) -> [u8; KEPT + 1] {
    let mut text = [b'.'; KEPT + 1];
    text[0] = b'0' + (n / 100_000_000) as u8;
    let rest = n % 100_000_000;
    let (high, low) = ((rest / 10_000) as usize, (rest % 10_000) as usize);
    for (at, pair) in [
        (2, high / 100),
        (4, high % 100),
        (6, low / 100),
        (8, low % 100),
    ] {
        text[at..at + 2].copy_from_slice(&PAIRS[2 * pair..][..2]);
    }
    text
}

/// The mantissa (`d.dddddddd`) and exponent of a value [`nine_digits`] leaves: rounded from
/// Żmij's shortest digits ([`nine_of_shortest`]); `None` where the standard library decides.
#[cold]
#[inline(never)]
fn rare_mantissa(value: f64) -> Option<([u8; KEPT + 1], i32)> {
    let mut buffer = zmij::Buffer::new();
    let (kept, exponent) = nine_of_shortest(value, buffer.format_finite(value).as_bytes())?;
    let mut mantissa = [b'.'; KEPT + 1];
    mantissa[0] = kept[0];
    mantissa[2..].copy_from_slice(&kept[1..]);
    Some((mantissa, exponent))
}

/// The [`KEPT`] significant digits of finite `value`, correctly rounded, as an integer `n`
/// (10^8 ≤ n < 10^9; 0 and the power 0 for zero), and the power of ten of the first, by one
/// multiplication or division with an exact power of ten: `|value| × 10^(8−k)` in [1e8, 1e9)
/// carries one rounding (≤ 1.2e-7 there), so rounding it to an integer is rounding the exact
/// value whenever its fraction is more than 1e-6 from ½. `None` for magnitudes outside
/// 1e-14…1e31 (the power would not be exact) and the near-ties.
#[inline]
fn nine_digits(value: f64) -> Option<(u32, i32)> {
    let magnitude = value.abs();
    if magnitude == 0.0 {
        return Some((0, 0));
    }
    if !(1e-14..1e31).contains(&magnitude) {
        return None;
    }
    // ⌊log10 2^binary⌋ (78913 / 2^18 = log10 2 to 1e-6: exact for |binary| < 1650, and
    // the shift rounds down for negatives too): k or k − 1.
    let binary = ((magnitude.to_bits() >> 52) as i32) - 1023;
    let mut k = (binary * 78913) >> 18;
    let scaled = |k: i32| -> Option<f64> {
        let p = 8 - k;
        let power = *POWERS_OF_TEN.get(p.unsigned_abs() as usize)?;
        Some(if p >= 0 {
            magnitude * power
        } else {
            magnitude / power
        })
    };
    let mut x = scaled(k)?;
    if x >= 1e9 {
        k += 1;
        x = scaled(k)?;
    }
    if !(1e8..1e9).contains(&x) {
        return None;
    }
    // x > 0: the conversion truncates, i.e. floors, and the difference is exact.
    let whole = x as u32;
    let fraction = x - f64::from(whole);
    if (fraction - 0.5).abs() < 1e-6 {
        return None;
    }
    let mut n = whole + u32::from(fraction > 0.5);
    if n == 1_000_000_000 {
        n = 100_000_000;
        k += 1;
    }
    Some((n, k))
}

/// The [`KEPT`] significant digits of finite `value` rounded from Żmij's shortest digits
/// (its `text`), and the power of ten of the first. For a normal `f64` that equals
/// rounding the exact value (its rounding interval, ~1e-16 relative, holds no two 10-digit
/// decimals) unless they end exactly on a tie (…5 after the last kept digit): `None` there,
/// and for subnormals and values that are themselves ties ([`Tie`]).
fn nine_of_shortest(value: f64, text: &[u8]) -> Option<([u8; KEPT], i32)> {
    let shortest = Shortest::read(text);
    let digits = shortest.digits();
    // Subnormals: their shortest digits may be fewer than nine and still not the value's.
    let subnormal = value != 0.0 && value.abs() < f64::MIN_POSITIVE;
    let rounding_tie = digits.len() == KEPT + 1 && digits[KEPT] == b'5';
    if subnormal || rounding_tie || tie(value).is(digits.len()) {
        return None;
    }
    let mut kept = [b'0'; KEPT];
    let n = digits.len().min(KEPT);
    kept[..n].copy_from_slice(&digits[..n]);
    let mut exponent = shortest.point - 1;
    if digits.len() > KEPT && digits[KEPT] >= b'5' {
        // Round up (not a tie: more digits follow the 5, or the digit is above 5).
        let mut k = KEPT;
        loop {
            if k == 0 {
                kept[0] = b'1';
                exponent += 1;
                break;
            }
            k -= 1;
            if kept[k] == b'9' {
                kept[k] = b'0';
            } else {
                kept[k] += 1;
                break;
            }
        }
    }
    if digits.is_empty() {
        exponent = 0;
    }
    Some((kept, exponent))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn scientific(v: f64) -> String {
        let mut out = Vec::new();
        push_scientific(v, 0, &mut out);
        String::from_utf8(out).unwrap()
    }

    /// Rounding up through nines, ties, zero, the ends of the exponent range.
    #[test]
    fn scientific_digits_match_the_standard_library_at_the_edges() {
        for v in [
            0.0,
            -0.0,
            1.0,
            9.999999995,
            9.9999999951,
            -9.99999999999,
            1.0000000005,
            1.00000000050001,
            123_456_789.5,
            1e-300,
            1.7976931348623157e308,
            5e-324,
            -3.085e6,
        ] {
            assert_eq!(scientific(v), format!("{:.8e}", v + 0.0), "{v:e}");
        }
        let mut padded = Vec::new();
        push_scientific(-0.5, 16, &mut padded);
        assert_eq!(padded, b"  -5.00000000e-1");
    }

    /// The table's scientific cells keep the sign of `-0`, as `{:.8e}` does.
    #[test]
    fn signed_scientific_cells_match_the_standard_library() {
        for v in [-0.0, 0.0, -1.0, 3.085e6, -5e-324, 9.999999995] {
            let mut out = Vec::new();
            push_scientific_signed(v, &mut out);
            assert_eq!(String::from_utf8(out).unwrap(), format!("{v:.8e}"), "{v:e}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]
        /// Any finite `f64` prints as `{:.8e}` prints it: the same nine digits.
        #[test]
        fn scientific_digits_match_the_standard_library(bits in any::<u64>()) {
            let v = f64::from_bits(bits);
            prop_assume!(v.is_finite());
            prop_assert_eq!(scientific(v), format!("{:.8e}", v + 0.0));
        }

        /// Values in the range of the fast path (1e-14…1e31, one product with an exact power
        /// of ten), of either sign: the same nine digits.
        #[test]
        fn scientific_digits_match_in_the_fast_range(
            fraction in 0u64..(1 << 52),
            exponent in 975u64..1127,
            negative in any::<bool>(),
        ) {
            let v = f64::from_bits((u64::from(negative) << 63) | (exponent << 52) | fraction);
            prop_assert_eq!(scientific(v), format!("{:.8e}", v + 0.0));
        }

        /// Values with few digits, where ties and carries are frequent.
        #[test]
        fn scientific_digits_match_at_short_decimals(m in 0u64..100_000_000_000, e in -20i32..20) {
            let v = m as f64 * 10f64.powi(e);
            prop_assert_eq!(scientific(v), format!("{:.8e}", v + 0.0));
        }
    }
}
