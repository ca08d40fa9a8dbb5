//! The run-time evaluator compiled to native code: a [`Program`]'s instruction list
//! translated once into one machine-code function by cranelift.
//!
//! Each register becomes an SSA value (cranelift allocates machine registers and spills);
//! `+ − × ÷`, `√`, negation, `|x|`, comparisons and selects are native instructions,
//! each rounded once as in the interpreter (no fused multiply-add: cranelift never fuses
//! on its own); an integer power is unrolled into the products [`f64::powi`] computes.
//! Every other primitive (`sin_cos`, `atan2`, `exp`, `hypot`, …) is a call to a small
//! `extern "C"` shim around the very Rust function the interpreter calls ([`f64::sin_cos`],
//! [`f64::atan2`], [`DualArithmetic`]), so the compiled code, the interpreter and
//! [`crate::symbolic::Graph::evaluate_f64`] agree to the bit.
//!
//! **Why a JIT beside the interpreter** (measured in `benches/scene_codegen.rs`, see
//! BENCHMARKS.md): the interpreter's cost is its dispatch, one indirect jump and the
//! loads and stores of registers per instruction; compiled code has neither. Compiling
//! costs more than the interpreter's set-up, so a caller chooses by how many evaluations
//! follow (`mechdiff run` by the number of drive positions).

use std::fmt;
use std::sync::{Arc, Mutex, PoisonError};

use cranelift_codegen::ir::condcodes::FloatCC;
use cranelift_codegen::ir::{
    AbiParam, FuncRef, InstBuilder, MemFlags, StackSlotData, StackSlotKind, Type, Value, types,
};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{FuncId, Linkage, Module, ModuleError, default_libcall_names};

use super::Program;
use super::program::Op;
use crate::Error;
use crate::symbolic::eval::{Arithmetic, DualArithmetic};
use crate::symbolic::{Binary, Comparison, Unary};

/// The compiled function: writes output `k` at drive position `phi` into `out[k]`.
type Function = unsafe extern "C" fn(phi: f64, out: *mut f64);

/// A [`Program`] compiled to native code: the same outputs, bit for bit, without an
/// interpreter's dispatch. Cloning shares the code; the code is freed with the last clone.
///
/// ```
/// use mechdiff_core::trace::{JitProgram, Program};
/// use mechdiff_core::symbolic::Graph;
/// let mut g = Graph::new();
/// let f = g.parse_infix("sin(phi) * cos(phi) + exp(phi) / 3").unwrap();
/// let program = Program::compile(&g, &[f], "phi").unwrap();
/// let (mut registers, mut interpreted) = (program.registers(), [0.0]);
/// program.evaluate(0.5, &mut registers, &mut interpreted);
/// match JitProgram::compile(&program) {
///     Ok(jit) => {
///         let mut out = [0.0];
///         jit.evaluate(0.5, &mut out);
///         assert_eq!(out[0].to_bits(), interpreted[0].to_bits());
///     }
///     // A host cranelift does not generate code for: the interpreter stays.
///     Err(e) => assert!(e.to_string().contains("native code")),
/// }
/// ```
#[derive(Clone)]
#[cfg_attr(docsrs, doc(cfg(feature = "jit")))]
pub struct JitProgram {
    code: Arc<Code>,
    outputs: usize,
}

/// The module owning the machine code, and the function in it.
struct Code {
    /// Only taken, to free the code, when the last [`JitProgram`] sharing it is dropped
    /// (a `Mutex` makes the module, which is `Send`, shareable between threads).
    module: Mutex<Option<JITModule>>,
    function: Function,
}

impl Drop for Code {
    fn drop(&mut self) {
        let module = self
            .module
            .get_mut()
            .unwrap_or_else(PoisonError::into_inner);
        if let Some(module) = module.take() {
            // SAFETY: the last owner of `function` is being dropped: no call of it is
            // running (calls borrow a `JitProgram`) and none can follow.
            unsafe { module.free_memory() };
        }
    }
}

impl fmt::Debug for JitProgram {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("JitProgram")
            .field("outputs", &self.outputs)
            .finish_non_exhaustive()
    }
}

impl JitProgram {
    /// Compiles `program` for the host.
    ///
    /// # Errors
    /// [`Error::JitUnavailable`] if cranelift does not generate code for the host's
    /// instruction set (or fails to compile: a bug, reported rather than run), or for a
    /// program of several inputs ([`Program::compile_inputs`]), which stays interpreted.
    pub fn compile(program: &Program) -> Result<Self, Error> {
        let unavailable = |reason: String| Error::JitUnavailable { reason };
        if program.inputs != 1 {
            // The compiled function takes the drive position alone; a program of several
            // inputs (a mixed plan's, [`Program::compile_inputs`]) stays interpreted.
            return Err(unavailable(format!(
                "the program has {} inputs; the JIT compiles programs of the drive position \
                 alone",
                program.inputs
            )));
        }
        let isa = cranelift_native::builder()
            .map_err(|m| unavailable(format!("cranelift does not support this host ({m})")))?;
        let mut flags = settings::builder();
        let verify = if cfg!(debug_assertions) {
            "true"
        } else {
            "false"
        };
        for (name, value) in [
            ("opt_level", "speed"),
            // Measured (callgrind, Whitworth's ψ program): 43 % fewer instructions to
            // compile than the backtracking allocator, 2.4 % more per evaluation.
            ("regalloc_algorithm", "single_pass"),
            // Calls to the shims by absolute address: the JIT's memory may lie anywhere.
            ("use_colocated_libcalls", "false"),
            ("is_pic", "false"),
            ("enable_verifier", verify),
        ] {
            flags
                .set(name, value)
                .map_err(|e| unavailable(format!("setting {name}: {e}")))?;
        }
        let isa = isa
            .finish(settings::Flags::new(flags))
            .map_err(|e| unavailable(e.to_string()))?;
        let mut builder = JITBuilder::with_isa(isa, default_libcall_names());
        let shims = shims();
        for shim in &shims {
            builder.symbol(&shim.name, shim.address);
        }
        let mut module = JITModule::new(builder);
        let function = define(&mut module, &shims, program)
            .and_then(|id| module.finalize_definitions().map_err(text).map(|()| id))
            .map(|id| module.get_finalized_function(id));
        match function {
            Ok(address) => Ok(JitProgram {
                code: Arc::new(Code {
                    module: Mutex::new(Some(module)),
                    // SAFETY: `define` gave the function this signature (`signature`):
                    // `(f64, pointer)`, no result, the host's C calling convention.
                    function: unsafe { std::mem::transmute::<*const u8, Function>(address) },
                }),
                outputs: program.outputs.len(),
            }),
            Err(e) => {
                // SAFETY: no pointer into the module was kept.
                unsafe { module.free_memory() };
                Err(unavailable(e))
            }
        }
    }

    /// Number of outputs.
    pub fn outputs(&self) -> usize {
        self.outputs
    }

    /// Evaluates at drive position `phi` into `out` (one value per output), as
    /// [`Program::evaluate`] does. Does not allocate.
    ///
    /// # Panics
    /// If `out` has fewer slots than outputs (a caller's bug).
    pub fn evaluate(&self, phi: f64, out: &mut [f64]) {
        assert!(
            out.len() >= self.outputs,
            "JitProgram::evaluate: one output slot per output"
        );
        // SAFETY: the function writes `out[0..self.outputs]` (one `f64` store per output,
        // `define`), which `out` holds; it reads nothing else but its constants and calls
        // only the shims, which touch nothing of the caller's. The code lives as long as
        // `self.code`.
        unsafe { (self.code.function)(phi, out.as_mut_ptr()) }
    }
}

/// A Rust function the compiled code calls.
struct Shim {
    name: String,
    address: *const u8,
    params: &'static [Type],
    returns: &'static [Type],
}

/// `(sin a, cos a)` into `out[0]`, `out[1]`, by [`f64::sin_cos`] as the interpreter.
///
/// # Safety
/// `out` must be valid for writing two `f64`s (the compiled code's stack slot).
unsafe extern "C" fn sin_cos(a: f64, out: *mut f64) {
    let (s, c) = a.sin_cos();
    // SAFETY: the caller's promise.
    unsafe { out.write(s) };
    // SAFETY: the caller's promise.
    unsafe { out.add(1).write(c) };
}

extern "C" fn atan2(a: f64, b: f64) -> f64 {
    a.atan2(b)
}

/// `Unary::ALL[K](a)` in the symbolic engine's `f64` arithmetic (one shim per primitive:
/// the primitive is known when the shim is compiled, so it dispatches nothing).
extern "C" fn unary<const K: usize>(a: f64) -> f64 {
    DualArithmetic::<f64>::new().unary(Unary::ALL[K], &a)
}

/// `Binary::ALL[K](a, b)` in the symbolic engine's `f64` arithmetic.
extern "C" fn binary<const K: usize>(a: f64, b: f64) -> f64 {
    DualArithmetic::<f64>::new().binary(Binary::ALL[K], &a, &b)
}

/// `[f::<0>, f::<1>, …]` as addresses.
macro_rules! instances {
    ($f:ident; $($k:literal)*) => {
        [$($f::<$k> as *const u8),*]
    };
}

const UNARY: [*const u8; 15] = instances!(unary; 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14);
const BINARY: [*const u8; 7] = instances!(binary; 0 1 2 3 4 5 6);
const _: () = assert!(UNARY.len() == Unary::ALL.len() && BINARY.len() == Binary::ALL.len());

const F64: Type = types::F64;
/// Pointers are passed as 64-bit integers (every host cranelift supports is 64-bit).
const PTR: Type = types::I64;

/// Index of the first unary shim in [`shims`] (the binary ones follow).
const FIRST_UNARY: usize = 2;

/// The shims: `sin_cos`, `atan2`, then one per unary and binary primitive.
fn shims() -> Vec<Shim> {
    let mut all = vec![
        Shim {
            name: "mechdiff_sin_cos".into(),
            address: sin_cos as *const u8,
            params: &[F64, PTR],
            returns: &[],
        },
        Shim {
            name: "mechdiff_atan2".into(),
            address: atan2 as *const u8,
            params: &[F64, F64],
            returns: &[F64],
        },
    ];
    for (op, &address) in Unary::ALL.iter().zip(&UNARY) {
        all.push(Shim {
            name: format!("mechdiff_{}", op.name()),
            address,
            params: &[F64],
            returns: &[F64],
        });
    }
    for (k, &address) in BINARY.iter().enumerate() {
        all.push(Shim {
            // Named by position: `+` and `-` are no symbol names.
            name: format!("mechdiff_binary_{k}"),
            address,
            params: &[F64, F64],
            returns: &[F64],
        });
    }
    all
}

/// The SSA value of each register, constants placed where first read.
struct Registers<'p> {
    values: Vec<Option<Value>>,
    initial: &'p [f64],
}

impl Registers<'_> {
    fn get(&mut self, b: &mut FunctionBuilder<'_>, r: u32) -> Value {
        let r = r as usize;
        match self.values[r] {
            Some(v) => v,
            None => {
                // A constant, the drive's placeholder aside (the drive is a parameter).
                let v = b.ins().f64const(self.initial[r]);
                self.values[r] = Some(v);
                v
            }
        }
    }
}

/// Declares and defines the function computing `program` in `module`, calling `shims`.
fn define(module: &mut JITModule, shims: &[Shim], program: &Program) -> Result<FuncId, String> {
    assert_eq!(
        module.target_config().pointer_type(),
        PTR,
        "cranelift-native supports 64-bit hosts only"
    );
    let signature = |module: &JITModule, params: &[Type], returns: &[Type]| {
        let mut s = module.make_signature();
        s.params.extend(params.iter().map(|&t| AbiParam::new(t)));
        s.returns.extend(returns.iter().map(|&t| AbiParam::new(t)));
        s
    };
    let mut ids = Vec::with_capacity(shims.len());
    for shim in shims {
        let s = signature(module, shim.params, shim.returns);
        ids.push(
            module
                .declare_function(&shim.name, Linkage::Import, &s)
                .map_err(text)?,
        );
    }
    let mut ctx = module.make_context();
    ctx.func.signature = signature(module, &[F64, PTR], &[]);
    let id = module
        .declare_anonymous_function(&ctx.func.signature)
        .map_err(text)?;
    let mut context = FunctionBuilderContext::new();
    let mut b = FunctionBuilder::new(&mut ctx.func, &mut context);
    // Each shim declared in the function where first called.
    let mut imported: Vec<Option<FuncRef>> = vec![None; shims.len()];
    let mut shim = |b: &mut FunctionBuilder<'_>, k: usize| {
        *imported[k].get_or_insert_with(|| module.declare_func_in_func(ids[k], b.func))
    };
    let block = b.create_block();
    b.append_block_params_for_function_params(block);
    b.switch_to_block(block);
    let (phi, out) = (b.block_params(block)[0], b.block_params(block)[1]);
    let pair = b.create_sized_stack_slot(StackSlotData::new(StackSlotKind::ExplicitSlot, 16, 3));
    let mut x = Registers {
        values: vec![None; program.initial.len()],
        initial: &program.initial,
    };
    x.values[program.drive as usize] = Some(phi);
    let (zero, one) = (b.ins().f64const(0.0), b.ins().f64const(1.0));
    for ins in &program.code {
        let a = x.get(&mut b, ins.a);
        let call = |b: &mut FunctionBuilder<'_>, f, args: &[Value]| {
            let call = b.ins().call(f, args);
            b.inst_results(call)[0]
        };
        let value = match ins.op {
            Op::Add => {
                let y = x.get(&mut b, ins.b);
                b.ins().fadd(a, y)
            }
            Op::Sub => {
                let y = x.get(&mut b, ins.b);
                b.ins().fsub(a, y)
            }
            Op::Mul => {
                let y = x.get(&mut b, ins.b);
                b.ins().fmul(a, y)
            }
            Op::Div => {
                let y = x.get(&mut b, ins.b);
                b.ins().fdiv(a, y)
            }
            Op::MulAdd | Op::MulSub | Op::SubMul => {
                let (y, c) = (x.get(&mut b, ins.b), x.get(&mut b, ins.c));
                let product = b.ins().fmul(a, y);
                match ins.op {
                    Op::MulAdd => b.ins().fadd(product, c),
                    Op::MulSub => b.ins().fsub(product, c),
                    _ => b.ins().fsub(c, product),
                }
            }
            Op::Neg => b.ins().fneg(a),
            Op::Sqrt => b.ins().sqrt(a),
            // `−a` for `a < 0`, else `a` (so −0 and NaN keep their sign, as the engine's).
            Op::Abs => {
                let negative = b.ins().fcmp(FloatCC::LessThan, a, zero);
                let minus = b.ins().fneg(a);
                b.ins().select(negative, minus, a)
            }
            Op::Atan2 => {
                let y = x.get(&mut b, ins.b);
                let f = shim(&mut b, 1);
                call(&mut b, f, &[a, y])
            }
            Op::SinCos => {
                let at = b.ins().stack_addr(PTR, pair, 0);
                let f = shim(&mut b, 0);
                b.ins().call(f, &[a, at]);
                let cos = b.ins().stack_load(F64, pair, 8);
                x.values[ins.to as usize + 1] = Some(cos);
                b.ins().stack_load(F64, pair, 0)
            }
            Op::Unary(op) => {
                let f = shim(&mut b, FIRST_UNARY + index(Unary::ALL, op));
                call(&mut b, f, &[a])
            }
            Op::Binary(op) => {
                let y = x.get(&mut b, ins.b);
                let f = shim(&mut b, FIRST_UNARY + UNARY.len() + index(Binary::ALL, op));
                call(&mut b, f, &[a, y])
            }
            Op::Powi => powi(&mut b, a, ins.c as i32, one),
            // 1 or 0, as the interpreter's register holds it.
            Op::Compare(cmp) => {
                let y = x.get(&mut b, ins.b);
                let holds = b.ins().fcmp(condition(cmp), a, y);
                b.ins().select(holds, one, zero)
            }
            Op::Choose => {
                let (then, otherwise) = (x.get(&mut b, ins.b), x.get(&mut b, ins.c));
                let taken = b.ins().fcmp(FloatCC::Equal, a, one);
                b.ins().select(taken, then, otherwise)
            }
        };
        x.values[ins.to as usize] = Some(value);
    }
    for (k, &r) in program.outputs.iter().enumerate() {
        let v = x.get(&mut b, r);
        let offset = i32::try_from(8 * k).expect("fewer than 2^28 outputs");
        b.ins().store(MemFlags::trusted(), v, out, offset);
    }
    b.ins().return_(&[]);
    b.seal_all_blocks();
    b.finalize();
    module.define_function(id, &mut ctx).map_err(text)?;
    Ok(id)
}

/// cranelift's error as text (its type is large: clippy's `result_large_err`).
fn text(e: ModuleError) -> String {
    e.to_string()
}

/// The position of `op` in `all`.
fn index<T: PartialEq>(all: &[T], op: T) -> usize {
    all.iter()
        .position(|o| *o == op)
        .expect("an operation of `ALL`")
}

/// `a` to the power `n` (a constant) by the steps of [`f64::powi`] (compiler-builtins'
/// `__powidf2`: square and multiply from the lowest bit, then one reciprocal for `n < 0`),
/// each product rounded as there: the interpreter's bits without a call.
fn powi(b: &mut FunctionBuilder<'_>, a: Value, n: i32, one: Value) -> Value {
    let (mut base, mut power, mut product) = (a, n.unsigned_abs(), one);
    loop {
        if power & 1 != 0 {
            product = b.ins().fmul(product, base);
        }
        power >>= 1;
        if power == 0 {
            break;
        }
        base = b.ins().fmul(base, base);
    }
    if n < 0 {
        b.ins().fdiv(one, product)
    } else {
        product
    }
}

/// The comparison as cranelift's condition, true or false on NaN as Rust's operator.
fn condition(cmp: Comparison) -> FloatCC {
    match cmp {
        Comparison::Less => FloatCC::LessThan,
        Comparison::LessEqual => FloatCC::LessThanOrEqual,
        Comparison::Greater => FloatCC::GreaterThan,
        Comparison::GreaterEqual => FloatCC::GreaterThanOrEqual,
        Comparison::Equal => FloatCC::Equal,
        // Unordered or not equal: true on NaN, as `!=`.
        Comparison::NotEqual => FloatCC::NotEqual,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::symbolic::{Graph, Id};

    /// Evaluates `exprs` in `x` by the interpreter and by the compiled code at `xs`: the
    /// same bits (both round every operation once, in the same order, and call the same
    /// functions for the rest), NaN compared as NaN (its payload is not specified).
    fn assert_same_bits(exprs: &[&str], xs: &[f64]) {
        let mut g = Graph::new();
        let ids: Vec<Id> = (exprs.iter())
            .map(|e| g.parse_infix_piecewise(e).unwrap())
            .collect();
        let program = Program::compile(&g, &ids, "x").unwrap();
        let jit = JitProgram::compile(&program).unwrap();
        let (mut registers, mut want) = (program.registers(), vec![0.0; ids.len()]);
        let mut got = vec![0.0; ids.len()];
        for &x in xs {
            program.evaluate(x, &mut registers, &mut want);
            jit.evaluate(x, &mut got);
            for (k, (o, w)) in got.iter().zip(&want).enumerate() {
                assert!(
                    o.to_bits() == w.to_bits() || (o.is_nan() && w.is_nan()),
                    "{} at x = {x}: compiled {o:e}, interpreted {w:e}",
                    exprs[k]
                );
            }
        }
    }

    /// Every kind of instruction: fused products, selects, `|x|` (−0 and NaN keep their
    /// sign), powers, the shimmed primitives, constants folded or read as outputs.
    #[test]
    fn compiled_code_computes_the_interpreters_bits() {
        assert_same_bits(
            &[
                "x * 0.1 + x * x * 0.3",
                "0.7 - x * 1.3",
                "x * sin(x) - cos(x) * 3",
                "if(x < 0.5, x * x + 1, sqrt(x) * 2 - x) + abs(x - 2) * atan2(x, 0.3)",
                "if(x >= 0.25, 1, 2) + if(x != 0, 3, 4) + if(x == 0, 5, 6) + if(x <= 1, 7, 8)",
                "if(x > 0.9, x, -x)",
                "x^3 * 0.5 + hypot(x, 2) * (x - 1) + x^-2",
                "exp(x) + ln(abs(x) + 1) + cbrt(x) + tan(x) + atan(x) + tanh(x)",
                "sinh(x) * cosh(x) + asin(x / 4) + acos(x / 5) + powf(abs(x) + 1, x)",
                "abs(x)",
                "-x / (x - 1)",
                "atan2(0.65, 0) + 2",
            ],
            &[
                -1.7,
                -0.0,
                0.0,
                0.25,
                0.5,
                0.9,
                1.0,
                3.3,
                f64::NAN,
                f64::INFINITY,
            ],
        );
    }

    /// The code lives as long as its last clone, on any thread.
    #[test]
    fn clones_share_the_code_across_threads() {
        let mut g = Graph::new();
        let f = g.parse_infix("sin(x) + x * x").unwrap();
        let program = Program::compile(&g, &[f], "x").unwrap();
        let jit = JitProgram::compile(&program).unwrap();
        let copy = jit.clone();
        drop(jit);
        let value = std::thread::spawn(move || {
            let mut out = [0.0];
            copy.evaluate(0.5, &mut out);
            out[0]
        })
        .join()
        .unwrap();
        let want = g.evaluate_f64(&[f], &[("x", 0.5)]).unwrap()[0];
        assert_eq!(value.to_bits(), want.to_bits());
    }

    /// A program of several inputs (a mixed plan's) is refused, not compiled with its
    /// other inputs frozen at their placeholder values.
    #[test]
    fn a_program_of_several_inputs_is_refused() {
        let mut g = Graph::new();
        let f = g.parse_infix("phi * q").unwrap();
        let program = Program::compile_inputs(&g, &[f], &["phi", "q"]).unwrap();
        match JitProgram::compile(&program) {
            Err(Error::JitUnavailable { reason }) => {
                assert!(reason.contains("2 inputs"), "{reason}")
            }
            other => panic!("expected JitUnavailable, got {:?}", other.map(|_| ())),
        }
    }
}
