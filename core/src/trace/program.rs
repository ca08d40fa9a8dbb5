//! The run-time back end: a graph compiled into a flat instruction list, evaluated in
//! `f64` without allocating.
//!
//! The constants are placed in registers once; each instruction writes one register,
//! reading registers written before it, so one pass in order evaluates the graph; a sine
//! and a cosine of one argument are one `sin_cos` call, as in the emitted Rust. The primitives are computed by the symbolic
//! engine's own `f64` arithmetic ([`DualArithmetic`]), so the evaluator and
//! [`Graph::evaluate_f64`] agree to the bit.
//!
//! **Why an interpreter and how it is kept fast** (measured in `benches/scene_codegen.rs`,
//! see BENCHMARKS.md): the cost of an interpreter is its dispatch — one indirect jump per
//! instruction — and the loads around it, not the arithmetic. So instructions are small
//! (20 bytes: an operation tag and `u32` registers), the destination of each is checked
//! once when the program is compiled (the loop reads and writes registers without bounds
//! checks), the few operations a mechanism needs most (`+ − × ÷`, `√`, `sin_cos`, `atan2`,
//! `|x|`) are dispatched directly, and a product used once by a sum or difference is fused
//! with it (`a·b + c`, still rounded twice: no fused multiply-add, so the results stay bit
//! for bit those of the emitted code), which removes about a third of the dispatches of a
//! differentiated mechanism.

use crate::Error;
use crate::symbolic::constants;
use crate::symbolic::eval::{Arithmetic, DualArithmetic};
use crate::symbolic::{Binary, Comparison, Graph, Id, Node, Unary};

/// What an instruction computes from its argument registers `a`, `b`, `c`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Op {
    Add,
    Sub,
    Mul,
    Div,
    /// `a·b + c`, each operation rounded (as the two nodes it replaces).
    MulAdd,
    /// `a·b − c`, each operation rounded.
    MulSub,
    /// `c − a·b`, each operation rounded.
    SubMul,
    Neg,
    Sqrt,
    /// `|a|` as the engine computes it (`−a` for `a < 0`, else `a`).
    Abs,
    /// `atan2(a, b)`: libm's, as the emitted code calls it.
    Atan2,
    /// `sin a` into the instruction's register, `cos a` into the next one.
    SinCos,
    Unary(Unary),
    Binary(Binary),
    /// `a` to the power `c` (an `i32` stored in the register field; never read as one).
    Powi,
    /// 1 if `a cmp b`, else 0 (the first half of a select).
    Compare(Comparison),
    /// `b` if `a` (a [`Op::Compare`] result) is 1, else `c`.
    Choose,
}

/// One instruction: `registers[to] = op(registers[a], registers[b], registers[c])`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Instruction {
    pub(super) op: Op,
    pub(super) to: u32,
    pub(super) a: u32,
    pub(super) b: u32,
    pub(super) c: u32,
}

impl Instruction {
    fn new(op: Op, to: u32, a: u32, b: u32, c: u32) -> Self {
        Instruction { op, to, a, b, c }
    }

    /// The registers the instruction reads.
    fn reads(&self) -> &'static [usize] {
        match self.op {
            Op::Neg | Op::Sqrt | Op::Abs | Op::SinCos | Op::Unary(_) | Op::Powi => &[0],
            Op::MulAdd | Op::MulSub | Op::SubMul | Op::Choose => &[0, 1, 2],
            _ => &[0, 1],
        }
    }

    fn operand(&self, k: usize) -> u32 {
        [self.a, self.b, self.c][k]
    }

    /// The registers the instruction writes, past the last one.
    fn end(&self) -> u32 {
        self.to + if self.op == Op::SinCos { 2 } else { 1 }
    }
}

/// A graph's outputs as an instruction list in one variable (the drive position).
///
/// ```
/// use mechdiff_core::trace::Program;
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
    /// The registers' initial values: the constants, the drive position (0), and the
    /// values of the instructions folded at compile time (every argument a constant).
    pub(super) initial: Vec<f64>,
    /// The drive position's register (the first input's, see [`Program::compile_inputs`]).
    pub(super) drive: u32,
    /// Number of inputs, in registers `drive..drive + inputs`.
    pub(super) inputs: u32,
    /// The instructions, in order; every register they name is below `size`.
    pub(super) code: Vec<Instruction>,
    pub(super) outputs: Vec<u32>,
    size: usize,
}

impl Program {
    /// Compiles `outputs` of `graph`, with `variable` the one input; named constants
    /// (`pi`, …) are constants.
    ///
    /// # Errors
    /// [`Error::UnboundSymbol`] for any other symbol.
    pub fn compile(graph: &Graph, outputs: &[Id], variable: &str) -> Result<Self, Error> {
        Self::compile_inputs(graph, outputs, &[variable])
    }

    /// Compiles `outputs` of `graph` with several inputs (`inputs[0]` the drive position),
    /// for [`Program::evaluate_inputs`]: a mixed plan's programs read the Newton loops'
    /// coordinates too (see [`super::NewtonBlock`]).
    ///
    /// # Errors
    /// [`Error::UnboundSymbol`] for a symbol that is neither an input nor a named constant.
    pub fn compile_inputs(graph: &Graph, outputs: &[Id], inputs: &[&str]) -> Result<Self, Error> {
        let variable = inputs.first().copied().unwrap_or(super::DRIVE);
        let input = |name: &str| inputs.iter().position(|&i| i == name);
        let needed = graph.reachable(outputs);
        let mut arithmetic = DualArithmetic::<f64>::new();
        // Constants first: their registers are written once, by `registers`.
        let mut register: Vec<u32> = vec![u32::MAX; graph.len()];
        let mut constants: Vec<f64> = Vec::new();
        for (index, node) in graph.nodes().iter().enumerate() {
            let value = match node {
                _ if !needed[index] => continue,
                Node::Num(n) => n.value(),
                Node::Sym(name) if &**name != variable && input(name).is_none() => arithmetic
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
        let count = inputs.len().max(1) as u32;
        constants.resize(constants.len() + count as usize, 0.0);
        let mut code: Vec<Instruction> = Vec::new();
        let mut next = drive + count;
        // The `SinCos` register of each argument whose sine or cosine is computed.
        let mut sin_cos: std::collections::HashMap<u32, u32> = Default::default();
        for (index, node) in graph.nodes().iter().enumerate() {
            if !needed[index] || register[index] != u32::MAX {
                continue;
            }
            let r = |id: &Id| register[id.index()];
            let (op, a, b, c) = match node {
                // Constants have their registers (above); the other symbols are inputs.
                Node::Num(_) => continue,
                Node::Sym(name) => {
                    register[index] = drive + input(name).unwrap_or(0) as u32;
                    continue;
                }
                Node::Unary(op @ (Unary::Sin | Unary::Cos), a) => {
                    let at = *sin_cos.entry(r(a)).or_insert_with(|| {
                        code.push(Instruction::new(Op::SinCos, next, r(a), 0, 0));
                        next += 2;
                        next - 2
                    });
                    register[index] = if *op == Unary::Sin { at } else { at + 1 };
                    continue;
                }
                Node::Unary(Unary::Neg, a) => (Op::Neg, r(a), 0, 0),
                Node::Unary(Unary::Sqrt, a) => (Op::Sqrt, r(a), 0, 0),
                Node::Unary(Unary::Abs, a) => (Op::Abs, r(a), 0, 0),
                Node::Unary(op, a) => (Op::Unary(*op), r(a), 0, 0),
                Node::Binary(Binary::Add, a, b) => (Op::Add, r(a), r(b), 0),
                Node::Binary(Binary::Sub, a, b) => (Op::Sub, r(a), r(b), 0),
                Node::Binary(Binary::Mul, a, b) => (Op::Mul, r(a), r(b), 0),
                Node::Binary(Binary::Div, a, b) => (Op::Div, r(a), r(b), 0),
                Node::Binary(Binary::Atan2, a, b) => (Op::Atan2, r(a), r(b), 0),
                Node::Binary(op, a, b) => (Op::Binary(*op), r(a), r(b), 0),
                Node::Powi(a, n) => (Op::Powi, r(a), 0, *n as u32),
                Node::Select(cmp, [a, b, then, otherwise]) => {
                    code.push(Instruction::new(Op::Compare(*cmp), next, r(a), r(b), 0));
                    next += 1;
                    (Op::Choose, next - 1, r(then), r(otherwise))
                }
            };
            register[index] = next;
            code.push(Instruction::new(op, next, a, b, c));
            next += 1;
        }
        let outputs: Vec<u32> = outputs.iter().map(|id| register[id.index()]).collect();
        let mut initial = constants;
        initial.resize(next as usize, 0.0);
        let mut program = Program {
            initial,
            drive,
            inputs: count,
            code,
            outputs,
            size: next as usize,
        };
        if !program.registers_in_order() {
            return Err(Error::Untraceable {
                operation: "a node read before it is computed (a bug of the evaluator)".to_owned(),
            });
        }
        program.fold_constants();
        program.code = fuse(
            std::mem::take(&mut program.code),
            &program.outputs,
            program.size,
        );
        Ok(program)
    }

    /// Computes once, into the initial registers, every instruction whose arguments are
    /// all constants (as `atan2(0.65, 0)` in a traced mechanism), with the same `f64`
    /// operations as [`Program::evaluate`]: the results are unchanged, bit for bit.
    fn fold_constants(&mut self) {
        let mut known = vec![false; self.size];
        known[..self.drive as usize].fill(true);
        let mut arithmetic = DualArithmetic::<f64>::new();
        let mut kept = Vec::with_capacity(self.code.len());
        for ins in std::mem::take(&mut self.code) {
            let constant = known[ins.b as usize]
                && ins.reads().iter().all(|&k| known[ins.operand(k) as usize]);
            if constant {
                // SAFETY: `compile` checked the instructions against `self.size`
                // (`registers_in_order`), the length of `self.initial`.
                unsafe { step(&ins, &mut self.initial, &mut arithmetic) };
                known[ins.to as usize..ins.end() as usize].fill(true);
            } else {
                kept.push(ins);
            }
        }
        self.code = kept;
    }

    /// Whether every instruction reads only registers written before it (constants, the
    /// drive, earlier instructions) and writes below `size`, and every output is a register:
    /// what [`Program::evaluate`] relies on to skip bounds checks.
    fn registers_in_order(&self) -> bool {
        let mut written = self.drive + self.inputs;
        let in_order = self.code.iter().all(|ins| {
            // `b` is read by every instruction (a register of its own, or 0).
            let reads = ins.b < ins.to && ins.reads().iter().all(|&k| ins.operand(k) < ins.to);
            let ok = reads && ins.to >= written && ins.end() as usize <= self.size;
            written = ins.end();
            ok
        });
        in_order
            && self.initial.len() == self.size
            && self.outputs.iter().all(|&r| (r as usize) < self.size)
    }

    /// Number of outputs.
    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }

    /// Number of instructions (after fusion; a `sin_cos` counts once).
    pub fn instructions(&self) -> usize {
        self.code.len()
    }

    /// The registers to evaluate with, the constants in place (allocate once, reuse for
    /// every evaluation).
    pub fn registers(&self) -> Vec<f64> {
        self.initial.clone()
    }

    /// Evaluates at the inputs `inputs` (in the order of [`Program::compile_inputs`]) into
    /// `out` (one value per output), with `registers` from [`Program::registers`]. Does not
    /// allocate.
    ///
    /// # Panics
    /// If `inputs`, `registers` or `out` are shorter than needed (a caller's bug).
    pub fn evaluate_inputs(&self, inputs: &[f64], registers: &mut [f64], out: &mut [f64]) {
        let at = self.drive as usize;
        registers[at..at + self.inputs as usize].copy_from_slice(&inputs[..self.inputs as usize]);
        self.evaluate(inputs[0], registers, out);
    }

    /// Evaluates at drive position `phi` into `out` (one value per output), with
    /// `registers` from [`Program::registers`]. Does not allocate.
    ///
    /// # Panics
    /// If `registers` or `out` are shorter than needed (a caller's bug).
    pub fn evaluate(&self, phi: f64, registers: &mut [f64], out: &mut [f64]) {
        assert!(
            registers.len() >= self.size && out.len() >= self.outputs.len(),
            "Program::evaluate: registers from Program::registers and one output slot each"
        );
        let x = &mut registers[..self.size];
        x[self.drive as usize] = phi;
        let mut arithmetic = DualArithmetic::<f64>::new();
        for ins in &self.code {
            // SAFETY: `compile` checked every instruction against `self.size`
            // (`registers_in_order`) and `x` has `self.size` registers.
            unsafe { step(ins, x, &mut arithmetic) };
        }
        for (o, &r) in out.iter_mut().zip(&self.outputs) {
            *o = x[r as usize];
        }
    }
}

/// Executes one instruction on the registers `x`.
///
/// # Safety
/// Every register `ins` names (`a`, `b`, `to`, and `c` where it reads it; `to + 1` for a
/// `sin_cos`) must be below `x.len()`: `registers_in_order` checks it for a program's
/// instructions against its number of registers.
#[inline(always)]
unsafe fn step(ins: &Instruction, x: &mut [f64], arithmetic: &mut DualArithmetic<f64>) {
    // SAFETY: the caller's promise (see above).
    let get = |r: u32| unsafe { *x.get_unchecked(r as usize) };
    let (a, b) = (get(ins.a), get(ins.b));
    let value = match ins.op {
        Op::Add => a + b,
        Op::Sub => a - b,
        Op::Mul => a * b,
        Op::Div => a / b,
        Op::MulAdd => a * b + get(ins.c),
        Op::MulSub => a * b - get(ins.c),
        Op::SubMul => get(ins.c) - a * b,
        Op::Neg => -a,
        Op::Sqrt => a.sqrt(),
        Op::Abs => {
            if a < 0.0 {
                -a
            } else {
                a
            }
        }
        Op::Atan2 => a.atan2(b),
        Op::SinCos => {
            let (s, c) = a.sin_cos();
            // SAFETY: as above; `registers_in_order` checked `to + 1` too.
            unsafe { *x.get_unchecked_mut(ins.to as usize + 1) = c };
            s
        }
        Op::Unary(op) => arithmetic.unary(op, &a),
        Op::Binary(op) => arithmetic.binary(op, &a, &b),
        Op::Powi => a.powi(ins.c as i32),
        Op::Compare(cmp) => f64::from(u8::from(cmp.holds(&a, &b))),
        Op::Choose => {
            if a == 1.0 {
                b
            } else {
                get(ins.c)
            }
        }
    };
    // SAFETY: as above.
    unsafe { *x.get_unchecked_mut(ins.to as usize) = value };
}

/// Fuses each product read once, by a sum or a difference, into it: `a·b + c`, `a·b − c`,
/// `c − a·b` (both orders of a sum: IEEE addition is commutative, bit for bit). The
/// product's instruction is dropped; its register is then never written nor read.
fn fuse(mut code: Vec<Instruction>, outputs: &[u32], size: usize) -> Vec<Instruction> {
    let mut reads = vec![0u32; size];
    for ins in &code {
        for &k in ins.reads() {
            reads[ins.operand(k) as usize] += 1;
        }
    }
    for &r in outputs {
        reads[r as usize] += 1;
    }
    // The instruction computing each register, when it is a product read once.
    let mut product = vec![usize::MAX; size];
    for (i, ins) in code.iter().enumerate() {
        if ins.op == Op::Mul && reads[ins.to as usize] == 1 {
            product[ins.to as usize] = i;
        }
    }
    let mut dropped = vec![false; code.len()];
    for i in 0..code.len() {
        let ins = code[i];
        let of = |r: u32| Some(product[r as usize]).filter(|&p| p != usize::MAX && !dropped[p]);
        let fused = match ins.op {
            Op::Add => of(ins.a)
                .map(|p| (p, Op::MulAdd, ins.b))
                .or_else(|| of(ins.b).map(|p| (p, Op::MulAdd, ins.a))),
            Op::Sub => of(ins.a)
                .map(|p| (p, Op::MulSub, ins.b))
                .or_else(|| of(ins.b).map(|p| (p, Op::SubMul, ins.a))),
            _ => None,
        };
        if let Some((p, op, c)) = fused {
            let m = code[p];
            code[i] = Instruction::new(op, ins.to, m.a, m.b, c);
            dropped[p] = true;
        }
    }
    code.into_iter()
        .zip(dropped)
        .filter(|(_, d)| !d)
        .map(|(ins, _)| ins)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fused and plain programs of the same expressions agree with the graph's own `f64`
    /// evaluation bit for bit (both round every operation once, in the same order).
    #[test]
    fn fused_products_round_as_the_graph_does() {
        let mut g = Graph::new();
        let exprs = [
            "x * 0.1 + x * x * 0.3",
            "0.7 - x * 1.3",
            "x * sin(x) - cos(x) * 3",
            "if(x < 0.5, x * x + 1, sqrt(x) * 2 - x) + abs(x - 2) * atan2(x, 0.3)",
            "x^3 * 0.5 + hypot(x, 2) * (x - 1)",
        ];
        let ids: Vec<Id> = (exprs.iter())
            .map(|e| g.parse_infix_piecewise(e).unwrap())
            .collect();
        let program = Program::compile(&g, &ids, "x").unwrap();
        assert!(program.code.iter().any(|i| i.op == Op::MulAdd));
        assert!(program.code.iter().any(|i| i.op == Op::SubMul));
        let (mut registers, mut out) = (program.registers(), vec![0.0; ids.len()]);
        for x in [-1.7, 0.0, 0.25, 0.5, 0.9, 3.3] {
            program.evaluate(x, &mut registers, &mut out);
            let want = g.evaluate_f64(&ids, &[("x", x)]).unwrap();
            for (k, (o, w)) in out.iter().zip(&want).enumerate() {
                assert_eq!(o.to_bits(), w.to_bits(), "{} at x = {x}", exprs[k]);
            }
        }
    }

    /// Constant subexpressions (`atan2(0.65, 0)`, `sin(2)` in a traced mechanism) are
    /// computed once, at compile time: only the two products of x and their sum remain,
    /// fused into one instruction after `x·c₁`.
    #[test]
    fn constant_subexpressions_are_folded() {
        let mut g = Graph::new();
        let f = g
            .parse_infix("atan2(0.65, 0) * x + sin(2) * cos(2) * x")
            .unwrap();
        let program = Program::compile(&g, &[f], "x").unwrap();
        assert!(
            !program
                .code
                .iter()
                .any(|i| matches!(i.op, Op::Atan2 | Op::SinCos)),
            "{:?}",
            program.code
        );
        let (mut registers, mut out) = (program.registers(), [0.0]);
        program.evaluate(0.7, &mut registers, &mut out);
        let want = g.evaluate_f64(&[f], &[("x", 0.7)]).unwrap()[0];
        assert_eq!(out[0].to_bits(), want.to_bits());
    }
}
