//! A generated scene of many names, for reading at scale (the test of 10⁵ names and
//! `examples/reading_names.rs`): the four-bar of `scenes/four_bar.toml` with `points`
//! coupler points `P0`, `P1`, … on its coupler and an `[[output]]` for each of the first
//! `outputs` of them (besides the rocker angle `psi`).

use std::fmt::Write as _;

/// The scene's text: 4 + `points` points, 4 links, 1 + `outputs` outputs, 3 positions.
pub fn many_names(points: usize, outputs: usize) -> String {
    let mut text = String::from(
        "title = \"many names\"\n[units]\nlength = \"m\"\nangle = \"deg\"\n\n[points]\n\
         O2 = [0.0, 0.0]\nO4 = [0.4, 0.0]\nA = [0.0, 0.1]\nB = [0.4, 0.3]\n",
    );
    for i in 0..points {
        let _ = writeln!(text, "P{i} = [{}, {}]", 0.3 + 1e-7 * i as f64, 0.45);
    }
    text.push_str(
        "\n[links]\nground = [\"O2\", \"O4\"]\ncrank = [\"O2\", \"A\"]\ncoupler = [\"A\", \"B\"",
    );
    for i in 0..points {
        let _ = write!(text, ", \"P{i}\"");
    }
    text.push_str(
        "]\nrocker = [\"O4\", \"B\"]\n\n[joints]\n\
         O2 = { type = \"revolute\", at = \"O2\", links = [\"ground\", \"crank\"] }\n\
         A = { type = \"revolute\", at = \"A\", links = [\"crank\", \"coupler\"] }\n\
         B = { type = \"revolute\", at = \"B\", links = [\"coupler\", \"rocker\"] }\n\
         O4 = { type = \"revolute\", at = \"O4\", links = [\"ground\", \"rocker\"] }\n\n\
         [drive]\njoint = \"O2\"\nline = [\"O2\", \"A\"]\nspeed = 10\n\n\
         [sweep]\nfrom = 0\nto = 10\nstep = 5\n\n\
         [[output]]\nname = \"psi\"\nangle = [\"O4\", \"B\"]\nquantities = [\"position\"]\n",
    );
    for i in 0..outputs.min(points) {
        let _ = write!(
            text,
            "\n[[output]]\npoint = \"P{i}\"\nquantities = [\"position\"]\n"
        );
    }
    text
}
