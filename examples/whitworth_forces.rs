//! The shaking force a Whitworth shaping machine puts on its foundation over one revolution,
//! and where it peaks. Run with `cargo run --release --example whitworth_forces`.

use mechdiff::mechanisms::Whitworth;
use mechdiff::mechanisms::whitworth::Parameters;
use mechdiff::report::fixed;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let shaper = Whitworth::reference();
    let drive = shaper.drive();
    println!(" φ [°]   ΣF_x [N]   ΣF_y [N]   |ΣF| [N]");
    let mut peak = (0.0, 0.0f64);
    for degrees in 0..360 {
        let phi = f64::from(degrees).to_radians();
        let f = shaper.shaking_force(phi, &drive)?;
        let magnitude = f.x.hypot(f.y);
        if magnitude > peak.1 {
            peak = (f64::from(degrees), magnitude);
        }
        if degrees % 30 == 0 {
            let [x, y, m] = [f.x, f.y, magnitude].map(|v| fixed(v, 2));
            println!("{degrees:>5}  {x:>9}  {y:>9}  {m:>9}");
        }
    }
    println!(
        "largest shaking force at 1° steps: {:.2} N at φ = {}°",
        peak.1, peak.0
    );

    // Faster crank, same machine: inertial forces grow with ω² (here ×2.25 at 150 rpm).
    let faster = Whitworth::new(Parameters {
        crank_speed: 150.0 * std::f64::consts::PI / 30.0,
        ..*shaper.parameters()
    })?;
    let [first, _] = faster.dead_positions()?;
    let f = faster.shaking_force(first.phi, &faster.drive())?;
    println!("at 150 rpm, first dead position: ΣF_x = {:.2} N", f.x);
    // Bad input is an error that names the parameter, never a NaN later.
    let broken = Whitworth::new(Parameters {
        m2: -30.0,
        ..Parameters::reference()
    });
    println!("m2 = −30 kg: {}", broken.unwrap_err());
    Ok(())
}
