//! The Whitworth shaping machine report: the source's table of accelerations and inertial
//! forces, recomputed, then the dead positions and the ram's stroke.

use super::{Table, fixed};
use mechdiff_core::PositionFunction;
use mechdiff_mechanisms::{Result, Whitworth};

/// The report for `shaper` at its constant crank speed: accelerations of S1, S2, S3 and the
/// inertial forces at φ = 0°, 180° and at both dead positions (found numerically, their exact
/// angles in the header), then the dead positions (φ, ψ, ψ″, x_C) and the ram's stroke.
///
/// ```
/// use mechdiff::mechanisms::Whitworth;
/// let text = mechdiff::report::whitworth::report(&Whitworth::reference())?;
/// assert!(text.contains("φ = 67.976°") && text.contains("1923.69"));
/// # Ok::<(), mechdiff::mechanisms::Error>(())
/// ```
pub fn report(shaper: &Whitworth) -> Result<String> {
    let p = shaper.parameters();
    let drive = shaper.drive();
    let dead = shaper.dead_positions()?;
    let angles = [0.0, std::f64::consts::PI, dead[0].phi, dead[1].phi];
    let mut columns = Vec::with_capacity(4);
    for phi in angles {
        let a = shaper.centre_accelerations(phi, &drive)?;
        let f = shaper.inertial_forces(phi, &drive)?;
        columns.push([
            a.s1.x, a.s1.y, a.s2.x, a.s2.y, a.s3.x, f.f1.x, f.f1.y, f.f2.x, f.f2.y, f.f3.x,
            f.sum.x, f.sum.y,
        ]);
    }
    let rows: [(&str, &str, usize); 12] = [
        ("ẍ_S1", "m/s²", 4),
        ("ÿ_S1", "m/s²", 4),
        ("ẍ_S2", "m/s²", 4),
        ("ÿ_S2", "m/s²", 4),
        ("ẍ_S3", "m/s²", 4),
        ("F_x1", "N", 2),
        ("F_y1", "N", 2),
        ("F_x2", "N", 2),
        ("F_y2", "N", 2),
        ("F_x3", "N", 2),
        ("ΣF_x", "N", 2),
        ("ΣF_y", "N", 2),
    ];
    let mut header = vec!["quantity".to_string(), "unit".to_string()];
    header.extend(angles.map(|phi| format!("φ = {}°", trimmed(phi.to_degrees(), 3))));
    let mut table = Table::new(2, header);
    for (r, (name, unit, decimals)) in rows.iter().enumerate() {
        let mut cells = vec![name.to_string(), unit.to_string()];
        cells.extend(columns.iter().map(|c| fixed(c[r], *decimals)));
        table.row(cells);
    }

    let mut dead_table = Table::new(
        1,
        ["", "φ [°]", "φ [rad]", "ψ [rad]", "ψ″ [1/rad]", "x_C [m]"]
            .map(String::from)
            .to_vec(),
    );
    let mut ram = [0.0; 2];
    for (k, (name, d)) in ["first", "second"].iter().zip(&dead).enumerate() {
        ram[k] = shaper.evaluate(d.phi).c.x;
        dead_table.row(vec![
            name.to_string(),
            fixed(d.phi.to_degrees(), 10),
            fixed(d.phi, 14),
            fixed(d.value, 12),
            fixed(d.d2, 12),
            fixed(ram[k], 12),
        ]);
    }

    let mut out = String::new();
    out.push_str("Whitworth shaping machine: inertial forces on the frame\n");
    out.push_str(&format!(
        "geometry: l0 = {} m, l1 = {} m (λ = {}), l_S1 = {} m, l_S2 = {} m, h = {} m\n",
        p.l0,
        p.l1,
        trimmed(shaper.lambda(), 6),
        p.l_s1,
        p.l_s2,
        p.h,
    ));
    out.push_str(&format!(
        "masses: m1 = {} kg, m2 = {} kg, m3 = {} kg; crank at constant speed ω = {} rad/s \
         ({} rpm)\n\n",
        p.m1,
        p.m2,
        p.m3,
        fixed(drive.omega, 6),
        trimmed(drive.omega * 30.0 / std::f64::consts::PI, 6)
    ));
    out.push_str(
        "Accelerations of the centres of gravity S1, S2, S3 and inertial forces F = −m·a\n\
         (the last two columns: the dead positions)\n\n",
    );
    out.push_str(&table.render());
    out.push_str("\nDead positions (ψ′ = 0, found numerically; cos φ = λ)\n\n");
    out.push_str(&dead_table.render());
    out.push_str(&format!(
        "\nRam stroke |x_C(φ₁) − x_C(φ₂)| = {} m\n",
        fixed((ram[0] - ram[1]).abs(), 12)
    ));
    Ok(out)
}

/// `value` with at most `decimals` decimals, trailing zeros dropped ("67.976", "100", "0.375").
fn trimmed(value: f64, decimals: usize) -> String {
    let text = fixed(value, decimals);
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}
