//! Column names as a picture prints them: Greek names as letters (`psi` → ψ), primes as
//! prime marks (`psi''` → ψ″), time derivatives as dots (`x_C_ddot` → ẍ_C), `Sum` as Σ.
//! Tables and CSV files keep the plain names; only labels of pictures change.

/// Greek letters by their spelled-out names.
const GREEK: [(&str, &str); 24] = [
    ("alpha", "α"),
    ("beta", "β"),
    ("gamma", "γ"),
    ("delta", "δ"),
    ("epsilon", "ε"),
    ("zeta", "ζ"),
    ("eta", "η"),
    ("theta", "θ"),
    ("iota", "ι"),
    ("kappa", "κ"),
    ("lambda", "λ"),
    ("mu", "μ"),
    ("nu", "ν"),
    ("xi", "ξ"),
    ("omicron", "ο"),
    ("pi", "π"),
    ("rho", "ρ"),
    ("sigma", "σ"),
    ("tau", "τ"),
    ("upsilon", "υ"),
    ("phi", "φ"),
    ("chi", "χ"),
    ("psi", "ψ"),
    ("omega", "ω"),
];

/// The picture label of a column or output name (see the module documentation).
pub fn symbol(name: &str) -> String {
    let (name, primes) = split_primes(name);
    let (name, dots) = split_dots(name);
    let name = match name.strip_prefix("Sum") {
        Some(rest) if !rest.is_empty() => format!("Σ{rest}"),
        _ => name.to_owned(),
    };
    // The first word (up to `_` or a digit) is a Greek letter if it spells one.
    let end = name
        .find(|c: char| c == '_' || c.is_ascii_digit())
        .unwrap_or(name.len());
    let (word, rest) = name.split_at(end);
    let word = GREEK
        .iter()
        .find(|(spelled, _)| *spelled == word)
        .map_or(word, |(_, letter)| letter);
    let mut out = String::new();
    let mut chars = word.chars();
    if let Some(first) = chars.next() {
        out.push(first);
        // Dots sit over the first letter: U+0307 (one), U+0308 (two), U+20DB (three).
        out.push_str(["", "\u{307}", "\u{308}", "\u{20db}"][dots]);
    }
    out.extend(chars);
    out.push_str(rest);
    out.push_str(["", "′", "″", "‴"][primes]);
    out
}

/// The name without its trailing primes (at most three) and their count.
fn split_primes(name: &str) -> (&str, usize) {
    let base = name.trim_end_matches('\'');
    let count = name.len() - base.len();
    if count <= 3 && !base.is_empty() {
        (base, count)
    } else {
        (name, 0)
    }
}

/// The name without a `_dot`, `_ddot` or `_dddot` suffix and the number of dots.
fn split_dots(name: &str) -> (&str, usize) {
    for (suffix, dots) in [("_dddot", 3), ("_ddot", 2), ("_dot", 1)] {
        if let Some(base) = name.strip_suffix(suffix)
            && !base.is_empty()
        {
            return (base, dots);
        }
    }
    (name, 0)
}

#[cfg(test)]
mod tests {
    use super::symbol;

    /// The names mechdiff writes for coefficients, derivatives and sums.
    #[test]
    fn names_become_symbols() {
        assert_eq!(symbol("psi''"), "ψ″");
        assert_eq!(symbol("psi'"), "ψ′");
        assert_eq!(symbol("x_C''"), "x_C″");
        assert_eq!(symbol("x_ddot"), "x\u{308}");
        assert_eq!(symbol("theta3_dot"), "θ\u{307}3");
        assert_eq!(symbol("SumF_x"), "ΣF_x");
        assert_eq!(symbol("M_drive"), "M_drive");
        assert_eq!(symbol("epsilon_lever"), "ε_lever");
        assert_eq!(symbol("Sum"), "Sum");
    }
}
