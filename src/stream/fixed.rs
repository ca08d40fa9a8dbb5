//! Fixed-point numbers for the table printed from its values: `value` with a given number of
//! decimals, written straight into the output buffer, byte for byte as
//! [`crate::report::fixed`] (`format!("{value:.decimals$}")` without the sign of a value
//! that rounds to zero) prints it.

/// Powers of ten exact in `f64`.
const POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Appends finite `value` with `decimals` decimals, correctly rounded, as
/// [`crate::report::fixed`] prints it (a value that rounds to zero has no minus sign).
///
/// ```
/// use mechdiff::stream::fixed::push_fixed;
///
/// let mut out = Vec::new();
/// push_fixed(-1.23456, 3, &mut out);
/// out.push(b' ');
/// push_fixed(-0.0001, 3, &mut out);
/// assert_eq!(out, b"-1.235 0.000");
/// ```
pub fn push_fixed(value: f64, decimals: usize, out: &mut Vec<u8>) {
    match scaled_integer(value, decimals) {
        Some(n) => {
            if n > 0 && value < 0.0 {
                out.push(b'-');
            }
            push_with_point(n, decimals, out);
        }
        None => out.extend_from_slice(crate::report::fixed(value, decimals).as_bytes()),
    }
}

/// `|value| × 10^decimals` rounded to the nearest integer, by one product with an exact power
/// of ten: below 1e9 the product carries one rounding of at most 2^-24 (≈ 6e-8), so rounding
/// it is rounding the exact value whenever its fraction is more than 1e-6 from ½. `None` for
/// larger products, more than 22 decimals, and the near-ties (the standard library decides
/// those, and rounds exact ties to even).
fn scaled_integer(value: f64, decimals: usize) -> Option<u64> {
    let power = *POWERS_OF_TEN.get(decimals)?;
    let x = value.abs() * power;
    if x >= 1e9 {
        return None;
    }
    // 0 ≤ x < 1e9: the conversion truncates, i.e. floors, and the difference is exact.
    let whole = x as u64;
    let fraction = x - whole as f64;
    if (fraction - 0.5).abs() < 1e-6 {
        return None;
    }
    Some(whole + u64::from(fraction > 0.5))
}

/// Appends `n / 10^decimals` with all its `decimals` decimals (`0.050` for 50 and 3).
fn push_with_point(n: u64, decimals: usize, out: &mut Vec<u8>) {
    let mut digits = [b'0'; 24];
    let mut len = 0;
    let mut rest = n;
    while rest > 0 || len <= decimals {
        digits[len] = b'0' + (rest % 10) as u8;
        rest /= 10;
        len += 1;
    }
    // `digits` holds at least `decimals + 1` digits, the last first.
    for (k, &d) in digits[..len].iter().enumerate().rev() {
        out.push(d);
        if k == decimals && decimals > 0 {
            out.push(b'.');
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn fixed(v: f64, decimals: usize) -> String {
        let mut out = Vec::new();
        push_fixed(v, decimals, &mut out);
        String::from_utf8(out).unwrap()
    }

    /// Zero of either sign, rounding to zero from below, carries through nines, exact ties
    /// (to even, decided by the standard library), the edge of the fast range.
    #[test]
    fn fixed_digits_match_the_standard_library_at_the_edges() {
        for (v, d) in [
            (0.0, 0),
            (-0.0, 3),
            (-0.0001, 3),
            (-0.0006, 3),
            (0.5, 0),
            (1.5, 0),
            (2.5, 0),
            (0.125, 2),
            (0.375, 2),
            (9.9995, 3),
            (-99.99999, 2),
            (999_999_999.4, 0),
            (1e9, 0),
            (123.456, 11),
            (1e300, 2),
            (5e-324, 11),
            (1.0, 22),
            (1.0, 23),
        ] {
            assert_eq!(fixed(v, d), crate::report::fixed(v, d), "{v:e} to {d}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]
        /// Any finite `f64` to 0–12 decimals (the table's columns use at most 11) prints as
        /// the standard library prints it.
        #[test]
        fn fixed_digits_match_the_standard_library(bits in any::<u64>(), d in 0usize..13) {
            let v = f64::from_bits(bits);
            prop_assume!(v.is_finite());
            prop_assert_eq!(fixed(v, d), crate::report::fixed(v, d));
        }

        /// Values of a table's magnitudes (the products in the fast range), of either sign,
        /// with few digits (ties and carries frequent) or many.
        #[test]
        fn fixed_digits_match_in_the_table_range(
            m in 0u64..10_000_000_000,
            e in -14i32..4,
            d in 0usize..12,
            negative in any::<bool>(),
            jitter in -2i64..3,
        ) {
            let v = m as f64 * 10f64.powi(e);
            let v = f64::from_bits((v.to_bits() as i64 + jitter).max(0) as u64);
            let v = if negative { -v } else { v };
            prop_assert_eq!(fixed(v, d), crate::report::fixed(v, d));
        }
    }
}
