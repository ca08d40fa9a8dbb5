//! The run-time back end: a graph compiled into a flat instruction list, evaluated in
//! `f64` without allocating.
//!
//! Each instruction writes one register (its own index), reading registers written before
//! it, so one pass in order evaluates the graph; a sine and a cosine of one argument are
//! one `sin_cos` call, as in the emitted Rust. The primitives are computed by the symbolic
//! engine's own `f64` arithmetic ([`DualArithmetic`]), so the evaluator and
//! [`Graph::evaluate_f64`] agree to the bit.

use crate::Error;
use crate::symbolic::constants;
use crate::symbolic::eval::{Arithmetic, DualArithmetic};
use crate::symbolic::{Binary, Comparison, Graph, Id, Node, Unary};

#[derive(Debug, Clone, Copy, PartialEq)]
enum Instruction {
    Constant(f64),
    Drive,
    Unary(Unary, u32),
    /// `sin` of the argument; the next register is its `cos`.
    SinCos(u32),
    /// Written by the `SinCos` before it.
    Cosine,
    Binary(Binary, u32, u32),
    Powi(u32, i32),
    Select(Comparison, [u32; 4]),
}

/// A graph's outputs as an instruction list in one variable (the drive position).
///
/// ```
/// use mechdiff_core::geometry::trace::Program;
/// use mechdiff_core::symbolic::Graph;
/// let mut g = Graph::new();
/// let f = g.parse_infix("sin(phi) * cos(phi) + pi").unwrap();
/// let program = Program::compile(&g, &[f], "phi").unwrap();
/// let (mut registers, mut out) = (program.registers(), [0.0]);
/// program.evaluate(0.5, &mut registers, &mut out);
/// assert_eq!(out[0], g.evaluate_f64(&[f], &[("phi", 0.5)]).unwrap()[0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    code: Vec<Instruction>,
    outputs: Vec<u32>,
}

impl Program {
    /// Compiles `outputs` of `graph`, with `variable` the one input; named constants
    /// (`pi`, …) are constants.
    ///
    /// # Errors
    /// [`Error::UnboundSymbol`] for any other symbol.
    pub fn compile(graph: &Graph, outputs: &[Id], variable: &str) -> Result<Self, Error> {
        let needed = graph.reachable(outputs);
        let mut register: Vec<u32> = vec![u32::MAX; graph.len()];
        let mut code: Vec<Instruction> = Vec::new();
        // The `SinCos` register of each argument whose sine or cosine is computed.
        let mut sin_cos: std::collections::HashMap<u32, u32> = Default::default();
        let mut arithmetic = DualArithmetic::<f64>::new();
        for (index, node) in graph.nodes().iter().enumerate() {
            if !needed[index] {
                continue;
            }
            let r = |id: &Id| register[id.index()];
            let here = code.len() as u32;
            register[index] = match node {
                Node::Num(n) => {
                    code.push(Instruction::Constant(n.value()));
                    here
                }
                Node::Sym(name) if &**name == variable => {
                    code.push(Instruction::Drive);
                    here
                }
                Node::Sym(name) => {
                    let value = arithmetic
                        .named_constant(name)
                        .filter(|_| constants::is_named_constant(name));
                    let value = value.ok_or_else(|| Error::UnboundSymbol {
                        symbol: name.to_string(),
                    })?;
                    code.push(Instruction::Constant(value));
                    here
                }
                Node::Unary(op @ (Unary::Sin | Unary::Cos), a) => {
                    let at = *sin_cos.entry(r(a)).or_insert_with(|| {
                        code.push(Instruction::SinCos(r(a)));
                        code.push(Instruction::Cosine);
                        here
                    });
                    if *op == Unary::Sin { at } else { at + 1 }
                }
                Node::Unary(op, a) => {
                    code.push(Instruction::Unary(*op, r(a)));
                    here
                }
                Node::Binary(op, a, b) => {
                    code.push(Instruction::Binary(*op, r(a), r(b)));
                    here
                }
                Node::Powi(a, n) => {
                    code.push(Instruction::Powi(r(a), *n));
                    here
                }
                Node::Select(cmp, ids) => {
                    code.push(Instruction::Select(*cmp, ids.map(|id| r(&id))));
                    here
                }
            };
        }
        let outputs = outputs.iter().map(|id| register[id.index()]).collect();
        Ok(Program { code, outputs })
    }

    /// Number of outputs.
    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }

    /// The registers to evaluate with (allocate once, reuse for every evaluation).
    pub fn registers(&self) -> Vec<f64> {
        vec![0.0; self.code.len()]
    }

    /// Evaluates at drive position `phi` into `out` (one value per output), with
    /// `registers` from [`Program::registers`]. Does not allocate.
    ///
    /// # Panics
    /// If `registers` or `out` are shorter than needed (a caller's bug).
    pub fn evaluate(&self, phi: f64, registers: &mut [f64], out: &mut [f64]) {
        let registers = &mut registers[..self.code.len()];
        let mut arithmetic = DualArithmetic::<f64>::new();
        for i in 0..self.code.len() {
            let value = match self.code[i] {
                Instruction::Constant(c) => c,
                Instruction::Drive => phi,
                Instruction::Unary(op, a) => arithmetic.unary(op, &registers[a as usize]),
                Instruction::SinCos(a) => {
                    let (s, c) = registers[a as usize].sin_cos();
                    registers[i + 1] = c;
                    s
                }
                Instruction::Cosine => continue,
                Instruction::Binary(op, a, b) => {
                    arithmetic.binary(op, &registers[a as usize], &registers[b as usize])
                }
                Instruction::Powi(a, n) => registers[a as usize].powi(n),
                Instruction::Select(cmp, [a, b, t, e]) => {
                    let holds = cmp.holds(&registers[a as usize], &registers[b as usize]);
                    registers[if holds { t } else { e } as usize]
                }
            };
            registers[i] = value;
        }
        for (o, &r) in out.iter_mut().zip(&self.outputs) {
            *o = registers[r as usize];
        }
    }
}
