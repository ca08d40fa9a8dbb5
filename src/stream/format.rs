//! Rows as text, fast: CSV and JSON Lines with the shortest digits that read back to the
//! same `f64` (the Żmij algorithm of the `zmij` crate), and the streamed table's fixed-width
//! scientific columns.

use crate::scene::outputs::Column;
use crate::scene::table::DIGITS;

/// The width of a number in the streamed table: `-d.dddddddde-308`, the longest an `f64`
/// prints in scientific notation with [`DIGITS`] significant digits.
pub const SCIENTIFIC_WIDTH: usize = DIGITS as usize + 7;

/// The shortest decimal digits of a finite `value` (no leading or trailing zeros; `0` has
/// none), the power of ten of the first digit's place plus one, and the sign.
struct Shortest {
    digits: [u8; 20],
    len: usize,
    /// The value is `0.d1d2d3… × 10^point`.
    point: i32,
    negative: bool,
}

impl Shortest {
    /// The digits of Żmij's text, which is `-`? then either `w.f` (no exponent: `w` is `0`
    /// or has no leading zero, `f` no trailing zero unless it is the `0` of `w.0`) or
    /// `d.ddde±x` / `de±x`: the crate gives its decimal only as text.
    fn read(text: &[u8]) -> Self {
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

    fn digits(&self) -> &[u8] {
        &self.digits[..self.len]
    }
}

/// Whether a finite `value` can lie exactly halfway between two decimals of few
/// significant digits (see [`Tie::is`]).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Tie {
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
fn tie(value: f64) -> Tie {
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
    fn is(self, len: usize) -> bool {
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
/// Most values take [`nine_digits`]; the others (zero, beyond 1e±14…1e31, or within 1e-6
/// of a rounding tie) round Żmij's shortest digits ([`nine_of_shortest`]) or, where that
/// cannot decide, let the standard library print them. The cell is laid out right-aligned in
/// a [`CELL`]-byte block and appended in one copy.
fn scientific(value: f64, width: usize, out: &mut Vec<u8>) {
    let (kept, exponent) = match nine_digits(value) {
        Some(nine) => nine,
        None => {
            let mut buffer = zmij::Buffer::new();
            match nine_of_shortest(value, buffer.format_finite(value).as_bytes()) {
                Some(nine) => nine,
                None => {
                    let _ = std::io::Write::write_fmt(
                        out,
                        format_args!("{:>width$.*e}", KEPT - 1, value),
                    );
                    return;
                }
            }
        }
    };
    let mut cell = [b' '; CELL];
    // The exponent's digits (no leading zero), its sign, the `e`, from the end.
    let magnitude = exponent.unsigned_abs() as usize;
    let places = 1 + usize::from(magnitude >= 10) + usize::from(magnitude >= 100);
    cell[CELL - 1] = b'0' + (magnitude % 10) as u8;
    cell[CELL - 2] = b'0' + (magnitude / 10 % 10) as u8;
    cell[CELL - 3] = b'0' + (magnitude / 100) as u8;
    let mut start = CELL - places;
    if exponent < 0 {
        start -= 1;
        cell[start] = b'-';
    }
    start -= 1;
    cell[start] = b'e';
    // `d.dddddddd`, and the sign.
    start -= KEPT + 1;
    cell[start] = kept[0];
    cell[start + 1] = b'.';
    cell[start + 2..start + KEPT + 1].copy_from_slice(&kept[1..]);
    if value.is_sign_negative() {
        start -= 1;
        cell[start] = b'-';
    }
    if width >= CELL {
        out.resize(out.len() + (width - CELL), b' ');
        out.extend_from_slice(&cell);
    } else {
        out.extend_from_slice(&cell[start.min(CELL - width)..]);
    }
}

/// The [`KEPT`] significant digits of finite `value`, correctly rounded, and the power of
/// ten of the first, by one multiplication or division with an exact power of ten: `|value|
/// × 10^(8−k)` in [1e8, 1e9) carries one rounding (≤ 1.2e-7 there), so rounding it to an
/// integer is rounding the exact value whenever its fraction is more than 1e-6 from ½.
/// `None` for zero, magnitudes outside 1e-14…1e31 (the power would not be exact) and the
/// near-ties.
fn nine_digits(value: f64) -> Option<([u8; KEPT], i32)> {
    let magnitude = value.abs();
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
    // The first digit, then the other eight two at a time.
    let mut digits = [b'0'; KEPT];
    digits[0] = b'0' + (n / 100_000_000) as u8;
    let mut rest = n % 100_000_000;
    for pair in (0..4).rev() {
        let p = 2 * (rest % 100) as usize;
        digits[1 + 2 * pair..3 + 2 * pair].copy_from_slice(&PAIRS[p..p + 2]);
        rest /= 100;
    }
    Some((digits, k))
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

/// Which texts rows are written into.
#[derive(Debug, Clone, Copy)]
pub struct Wanted {
    /// The streamed table.
    pub table: bool,
    /// CSV.
    pub csv: bool,
    /// JSON Lines.
    pub jsonl: bool,
}

/// The text of some rows, one buffer per output (kept and reused from batch to batch).
#[derive(Debug, Default)]
pub struct Texts {
    /// The streamed table's lines.
    pub table: Vec<u8>,
    /// CSV lines.
    pub csv: Vec<u8>,
    /// JSON Lines records.
    pub jsonl: Vec<u8>,
}

impl Texts {
    /// Empties every buffer, keeping its memory.
    pub fn clear(&mut self) {
        self.table.clear();
        self.csv.clear();
        self.jsonl.clear();
    }
}

/// How rows become text, one writer per output; the values of a row are in SI and printed
/// in the columns' units.
#[derive(Debug, Clone)]
pub struct RowFormat {
    /// Per column: the SI value per printed unit.
    factors: Vec<f64>,
    /// Per column: `"name [unit]":` as a JSON key, the first with its `{`.
    keys: Vec<String>,
    /// Per column: the streamed table's width.
    widths: Vec<usize>,
}

impl RowFormat {
    /// The format of rows with these columns.
    pub fn new(columns: &[Column]) -> Self {
        let keys = (columns.iter().enumerate())
            .map(|(k, c)| {
                let key = serde_json::Value::String(c.header()).to_string();
                format!("{}{key}:", if k == 0 { "{" } else { "," })
            })
            .collect();
        let widths = (columns.iter())
            .map(|c| {
                let unit = c.unit.chars().count() + 2;
                SCIENTIFIC_WIDTH.max(c.name.chars().count()).max(unit)
            })
            .collect();
        Self {
            factors: columns.iter().map(|c| c.factor).collect(),
            keys,
            widths,
        }
    }

    /// The number of columns.
    pub fn columns(&self) -> usize {
        self.factors.len()
    }

    /// The lines of a row in every text `wanted`, appended to `texts`: the CSV line (every
    /// value with the digits of [`push_display`]), the JSON Lines record
    /// (`{"name [unit]":value,...}`, Żmij's shortest digits) and the streamed table's line
    /// (every value as [`push_scientific`] writes it, right-aligned in its column's fixed
    /// width). Each value is formatted by Żmij at most once, for CSV and JSON Lines both;
    /// which texts are written is decided once per row, not per value.
    pub fn row(&self, row: &[f64], wanted: Wanted, texts: &mut Texts) {
        match (wanted.csv, wanted.jsonl) {
            (true, false) => self.csv_line(row, &mut texts.csv),
            (false, false) => {}
            (csv, jsonl) => self.shortest_lines(row, csv, jsonl, texts),
        }
        if wanted.table {
            self.table_line(row, &mut texts.table);
        }
    }

    /// A row's CSV line alone (the usual case): per value Żmij's text, laid out by
    /// [`display`].
    fn csv_line(&self, row: &[f64], out: &mut Vec<u8>) {
        let mut buffer = zmij::Buffer::new();
        for (k, (v, factor)) in row.iter().zip(&self.factors).enumerate() {
            let value = v / factor + 0.0;
            if k > 0 {
                out.push(b',');
            }
            display(value, buffer.format_finite(value).as_bytes(), out);
        }
        out.push(b'\n');
    }

    /// A row's JSON Lines record, and its CSV line if `csv`, from one Żmij text per value.
    fn shortest_lines(&self, row: &[f64], csv: bool, jsonl: bool, texts: &mut Texts) {
        let mut buffer = zmij::Buffer::new();
        for (k, ((v, factor), key)) in row.iter().zip(&self.factors).zip(&self.keys).enumerate() {
            let value = v / factor + 0.0;
            let text = buffer.format_finite(value).as_bytes();
            if csv {
                if k > 0 {
                    texts.csv.push(b',');
                }
                display(value, text, &mut texts.csv);
            }
            if jsonl {
                texts.jsonl.extend_from_slice(key.as_bytes());
                texts.jsonl.extend_from_slice(text);
            }
        }
        if csv {
            texts.csv.push(b'\n');
        }
        if jsonl {
            texts.jsonl.extend_from_slice(b"}\n");
        }
    }

    /// A row's line of the streamed table: every value in scientific notation, right-aligned
    /// in its column, two spaces between columns.
    fn table_line(&self, row: &[f64], out: &mut Vec<u8>) {
        let columns = row.iter().zip(&self.factors).zip(&self.widths);
        for (k, ((v, factor), &width)) in columns.enumerate() {
            if k > 0 {
                out.extend_from_slice(b"  ");
            }
            scientific(v / factor + 0.0, width, out);
        }
        out.push(b'\n');
    }

    /// The two header lines of the streamed table: names, then units in brackets, each
    /// right-aligned in its column.
    pub fn table_header(&self, columns: &[Column], out: &mut String) {
        let line = |out: &mut String, cell: &dyn Fn(&Column) -> String| {
            let cells: Vec<String> = (columns.iter().zip(&self.widths))
                .map(|(c, &w)| format!("{:>w$}", cell(c)))
                .collect();
            out.push_str(cells.join("  ").trim_end());
            out.push('\n');
        };
        line(out, &|c| c.name.clone());
        line(out, &|c| format!("[{}]", c.unit));
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
            -842335545753126.25,
            0.5,
            180.0,
            3085085.0610378026,
            -3_085_085.023_246_659_4,
        ] {
            assert_eq!(display(v), (v + 0.0).to_string(), "{v:e}");
        }
    }

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

        /// A row's three texts, against the standard library cell by cell: CSV as `Display`
        /// prints each value, the streamed table as `{:.8e}` right-aligned in its width, and
        /// JSON Lines reading back as the same numbers under the CSV's headers.
        #[test]
        fn a_row_is_written_as_the_standard_library_writes_each_value(
            row in proptest::collection::vec(-1e7f64..1e7, 3),
            scale in -12i32..12,
            wanted in (any::<bool>(), any::<bool>(), any::<bool>()),
        ) {
            let columns = [("phi", "deg", 0.017453292519943295), ("s", "mm", 1e-3), ("F,x", "N", 1.0)]
                .map(|(name, unit, factor)| Column { name: name.into(), unit: unit.into(), factor });
            let row: Vec<f64> = row.iter().map(|v| v * 10f64.powi(scale)).collect();
            let (table, csv, jsonl) = wanted;
            let mut texts = Texts::default();
            RowFormat::new(&columns).row(&row, Wanted { table, csv, jsonl }, &mut texts);
            let values: Vec<f64> = (row.iter().zip(&columns)).map(|(v, c)| v / c.factor + 0.0).collect();
            let csv_line = values.iter().map(f64::to_string).collect::<Vec<_>>().join(",") + "\n";
            prop_assert_eq!(String::from_utf8(texts.csv).unwrap(), if csv { csv_line } else { String::new() });
            let table_line = (values.iter())
                .map(|v| format!("{v:>SCIENTIFIC_WIDTH$.8e}"))
                .collect::<Vec<_>>()
                .join("  ")
                + "\n";
            prop_assert_eq!(String::from_utf8(texts.table).unwrap(), if table { table_line } else { String::new() });
            if jsonl {
                let record: serde_json::Map<String, serde_json::Value> =
                    serde_json::from_slice(&texts.jsonl).unwrap();
                for (c, v) in columns.iter().zip(&values) {
                    prop_assert_eq!(record[&c.header()].as_f64(), Some(*v));
                }
            } else {
                prop_assert!(texts.jsonl.is_empty());
            }
        }

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
