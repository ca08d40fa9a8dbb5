//! The run-time back end: a graph compiled into a flat instruction list, evaluated in
//! `f64` without allocating.
//!
//! The constants are placed in registers once; each instruction writes one register,
//! reading registers written before it, so one pass in order evaluates the graph; a sine
//! and a cosine of one argument are one `sin_cos` call, as in the emitted Rust. The primitives are computed by the symbolic
//! engine's own `f64` arithmetic ([`DualArithmetic`]), so the evaluator and
//! [`Graph::evaluate_f64`] agree to the bit.

use crate::Error;
use crate::symbolic::constants;
use crate::symbolic::eval::{Arithmetic, DualArithmetic};
use crate::symbolic::{Binary, Comparison, Graph, Id, Node, Unary};

/// What an instruction computes from its argument registers.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Op {
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    Neg(u32),
    Sqrt(u32),
    /// `sin` into the instruction's register, `cos` into the next one.
    SinCos(u32),
    Unary(Unary, u32),
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
    /// The registers' initial values: the constants, then the drive position (0).
    constants: Vec<f64>,
    /// Each instruction and the register it writes (after the constants and the drive).
    code: Vec<(u32, Op)>,
    outputs: Vec<u32>,
    size: usize,
}

impl Program {
    /// Compiles `outputs` of `graph`, with `variable` the one input; named constants
    /// (`pi`, …) are constants.
    ///
    /// # Errors
    /// [`Error::UnboundSymbol`] for any other symbol.
    pub fn compile(graph: &Graph, outputs: &[Id], variable: &str) -> Result<Self, Error> {
        let needed = graph.reachable(outputs);
        let mut arithmetic = DualArithmetic::<f64>::new();
        // Constants first: their registers are written once, by `registers`.
        let mut register: Vec<u32> = vec![u32::MAX; graph.len()];
        let mut constants: Vec<f64> = Vec::new();
        for (index, node) in graph.nodes().iter().enumerate() {
            let value = match node {
                _ if !needed[index] => continue,
                Node::Num(n) => n.value(),
                Node::Sym(name) if &**name != variable => arithmetic
                    .named_constant(name)
                    .filter(|_| constants::is_named_constant(name))
                    .ok_or_else(|| Error::UnboundSymbol {
                        symbol: name.to_string(),
                    })?,
                _ => continue,
            };
            register[index] = constants.len() as u32;
            constants.push(value);
        }
        let drive = constants.len() as u32;
        constants.push(0.0);
        let mut code: Vec<(u32, Op)> = Vec::new();
        let mut next = drive + 1;
        // The `SinCos` register of each argument whose sine or cosine is computed.
        let mut sin_cos: std::collections::HashMap<u32, u32> = Default::default();
        for (index, node) in graph.nodes().iter().enumerate() {
            if !needed[index] || register[index] != u32::MAX {
                continue;
            }
            let r = |id: &Id| register[id.index()];
            let op = match node {
                // Constants have their registers (above); the one other symbol is φ.
                Node::Num(_) => continue,
                Node::Sym(_) => {
                    register[index] = drive;
                    continue;
                }
                Node::Unary(op @ (Unary::Sin | Unary::Cos), a) => {
                    let at = *sin_cos.entry(r(a)).or_insert_with(|| {
                        code.push((next, Op::SinCos(r(a))));
                        next += 2;
                        next - 2
                    });
                    register[index] = if *op == Unary::Sin { at } else { at + 1 };
                    continue;
                }
                Node::Unary(Unary::Neg, a) => Op::Neg(r(a)),
                Node::Unary(Unary::Sqrt, a) => Op::Sqrt(r(a)),
                Node::Unary(op, a) => Op::Unary(*op, r(a)),
                Node::Binary(Binary::Add, a, b) => Op::Add(r(a), r(b)),
                Node::Binary(Binary::Sub, a, b) => Op::Sub(r(a), r(b)),
                Node::Binary(Binary::Mul, a, b) => Op::Mul(r(a), r(b)),
                Node::Binary(Binary::Div, a, b) => Op::Div(r(a), r(b)),
                Node::Binary(op, a, b) => Op::Binary(*op, r(a), r(b)),
                Node::Powi(a, n) => Op::Powi(r(a), *n),
                Node::Select(cmp, ids) => Op::Select(*cmp, ids.map(|id| r(&id))),
            };
            register[index] = next;
            code.push((next, op));
            next += 1;
        }
        let outputs = outputs.iter().map(|id| register[id.index()]).collect();
        Ok(Program {
            constants,
            code,
            outputs,
            size: next as usize,
        })
    }

    /// Number of outputs.
    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }

    /// The registers to evaluate with, the constants in place (allocate once, reuse for
    /// every evaluation).
    pub fn registers(&self) -> Vec<f64> {
        let mut registers = self.constants.clone();
        registers.resize(self.size, 0.0);
        registers
    }

    /// Evaluates at drive position `phi` into `out` (one value per output), with
    /// `registers` from [`Program::registers`]. Does not allocate.
    ///
    /// # Panics
    /// If `registers` or `out` are shorter than needed (a caller's bug).
    pub fn evaluate(&self, phi: f64, registers: &mut [f64], out: &mut [f64]) {
        let x = &mut registers[..self.size];
        x[self.constants.len() - 1] = phi;
        let mut arithmetic = DualArithmetic::<f64>::new();
        for &(to, op) in &self.code {
            let at = |r: u32| r as usize;
            x[at(to)] = match op {
                Op::Add(a, b) => x[at(a)] + x[at(b)],
                Op::Sub(a, b) => x[at(a)] - x[at(b)],
                Op::Mul(a, b) => x[at(a)] * x[at(b)],
                Op::Div(a, b) => x[at(a)] / x[at(b)],
                Op::Neg(a) => -x[at(a)],
                Op::Sqrt(a) => x[at(a)].sqrt(),
                Op::SinCos(a) => {
                    let (s, c) = x[at(a)].sin_cos();
                    x[at(to) + 1] = c;
                    s
                }
                Op::Unary(op, a) => arithmetic.unary(op, &x[at(a)]),
                Op::Binary(op, a, b) => arithmetic.binary(op, &x[at(a)], &x[at(b)]),
                Op::Powi(a, n) => x[at(a)].powi(n),
                Op::Select(cmp, [a, b, t, e]) => {
                    let holds = cmp.holds(&x[at(a)], &x[at(b)]);
                    x[at(if holds { t } else { e })]
                }
            };
        }
        for (o, &r) in out.iter_mut().zip(&self.outputs) {
            *o = x[r as usize];
        }
    }
}
