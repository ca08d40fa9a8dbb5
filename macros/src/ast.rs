//! Stage 1: the function's Rust into the engine's IR.
//!
//! `let` bindings become names of IR nodes (the IR is a DAG, so a name is just an id);
//! every unsupported construct becomes an error spanned on it, and lowering goes on so that
//! all problems are reported at once (combined with `syn::Error::combine`).

use std::collections::HashMap;

use mechdiff_core::symbolic::{Binary, Comparison, Graph, Id, Unary};
use quote::ToTokens;
use syn::{BinOp, Block, Expr, FnArg, Ident, ItemFn, Lit, Pat, ReturnType, Stmt, Type, UnOp};

/// The function in the engine's IR.
pub struct Lowered {
    /// The graph holding the value (and, later, its derivatives).
    pub graph: Graph,
    /// The function's value.
    pub value: Id,
    /// The parameters, in order.
    pub parameters: Vec<Ident>,
}

const SUPPORTED: &str = "supported are `let` bindings, `+ - * /`, negation, f64 literals, \
parameters, constants, the f64 methods listed in the docs of `#[derivatives]` and `if`/`else` \
on comparisons";

const METHODS: &str = "sqrt, cbrt, exp, ln, sin, cos, tan, asin, acos, atan, sinh, cosh, \
tanh, abs, recip, powi, powf, atan2, hypot";

struct Lowering {
    graph: Graph,
    scopes: Vec<HashMap<String, Id>>,
    errors: Option<syn::Error>,
    error_count: usize,
}

fn is_f64(ty: &Type) -> bool {
    matches!(ty, Type::Path(path) if path.qself.is_none() && path.path.is_ident("f64"))
}

impl Lowering {
    fn error(&mut self, tokens: impl ToTokens, message: impl std::fmt::Display) -> Id {
        let error = syn::Error::new_spanned(tokens, message);
        self.error_count += 1;
        match &mut self.errors {
            Some(errors) => errors.combine(error),
            None => self.errors = Some(error),
        }
        // a placeholder, so that lowering goes on and finds the other problems
        self.graph.number(0.0)
    }

    fn lookup(&self, name: &str) -> Option<Id> {
        self.scopes
            .iter()
            .rev()
            .find_map(|scope| scope.get(name).copied())
    }

    fn parameters(&mut self, function: &ItemFn) -> Vec<Ident> {
        let signature = &function.sig;
        if !signature.generics.params.is_empty() {
            self.error(&signature.generics, "generic functions are not supported by #[derivatives]; write the function for `f64`");
        }
        match &signature.output {
            ReturnType::Type(_, ty) if is_f64(ty) => {}
            other => {
                self.error(other, "#[derivatives] needs a function returning `f64`");
            }
        }
        let mut parameters = Vec::new();
        for input in &signature.inputs {
            match input {
                FnArg::Typed(typed) => {
                    if !is_f64(&typed.ty) {
                        self.error(
                            &typed.ty,
                            "parameters must be `f64`; pass every quantity as an `f64` parameter",
                        );
                    }
                    match &*typed.pat {
                        Pat::Ident(ident)
                            if ident.by_ref.is_none()
                                && ident.mutability.is_none()
                                && ident.subpat.is_none() =>
                        {
                            let id = self.graph.symbol(&ident.ident.to_string());
                            self.scopes[0].insert(ident.ident.to_string(), id);
                            parameters.push(ident.ident.clone());
                        }
                        Pat::Ident(ident) if ident.mutability.is_some() => {
                            self.error(&typed.pat, "mutation is not supported: drop `mut` and bind new values with `let`");
                        }
                        other => {
                            self.error(other, "parameters must be plain names (`phi: f64`)");
                        }
                    }
                }
                FnArg::Receiver(receiver) => {
                    self.error(receiver, "methods are not supported by #[derivatives]; write a free function of `f64` parameters");
                }
            }
        }
        parameters
    }

    fn block(&mut self, block: &Block) -> Id {
        self.scopes.push(HashMap::new());
        let mut value = None;
        for (index, statement) in block.stmts.iter().enumerate() {
            let last = index + 1 == block.stmts.len();
            match statement {
                Stmt::Local(local) => {
                    let Some(init) = &local.init else {
                        self.error(local, "a `let` needs a value: `let x = <expression>;`");
                        continue;
                    };
                    if let Some((else_token, _)) = &init.diverge {
                        self.error(
                            else_token,
                            "`let … else` is not supported; use `if`/`else` on a comparison",
                        );
                    }
                    let id = self.expr(&init.expr);
                    let pattern = match &local.pat {
                        Pat::Type(typed) => &*typed.pat,
                        other => other,
                    };
                    match pattern {
                        Pat::Ident(ident) if ident.mutability.is_some() => {
                            self.error(ident, "mutation is not supported: drop `mut` and bind each new value with its own `let`");
                        }
                        Pat::Ident(ident) if ident.by_ref.is_none() && ident.subpat.is_none() => {
                            let scope = self.scopes.last_mut().expect("a scope is open");
                            scope.insert(ident.ident.to_string(), id);
                        }
                        other => {
                            self.error(other, "only plain names can be bound (`let x = …;`); destructuring is not supported");
                        }
                    }
                }
                Stmt::Expr(expr, None) if last => value = Some(self.expr(expr)),
                Stmt::Expr(expr @ (Expr::Assign(_) | Expr::Binary(_)), Some(_))
                    if is_mutation(expr) =>
                {
                    self.error(expr, "mutation is not supported: bind the new value with `let` instead of assigning");
                }
                Stmt::Expr(Expr::Return(ret), _) => {
                    self.error(ret, "`return` is not supported; end the function with its value as the tail expression");
                }
                Stmt::Expr(expr, _) => {
                    let errors_before = self.error_count;
                    self.expr(expr);
                    if !last && self.error_count == errors_before {
                        self.error(
                            expr,
                            "statements other than `let` have no effect here; remove it",
                        );
                    }
                }
                Stmt::Item(item) => {
                    self.error(item, "items inside the function are not supported; move the item out of the function");
                }
                Stmt::Macro(mac) => {
                    self.error(
                        mac,
                        "macros are not expanded by #[derivatives]; write the expression out",
                    );
                }
            }
        }
        self.scopes.pop();
        value.unwrap_or_else(|| {
            self.error(
                block,
                "the block needs a value: end it with an expression (no `;`)",
            )
        })
    }

    fn expr(&mut self, expr: &Expr) -> Id {
        match expr {
            Expr::Lit(literal) => match &literal.lit {
                Lit::Float(float) => match float.base10_parse::<f64>() {
                    Ok(value) if value.is_finite() => self.graph.number(value),
                    _ => self.error(float, "the literal is not a finite f64"),
                },
                Lit::Int(int) => self.error(
                    int,
                    format!(
                        "integer literal in an f64 expression; write `{}.0`",
                        int.base10_digits()
                    ),
                ),
                other => self.error(other, "only f64 literals are supported"),
            },
            Expr::Path(path) => {
                if path.qself.is_some() {
                    return self.error(
                        path,
                        "qualified paths are not supported; use a plain constant name",
                    );
                }
                if let Some(ident) = path.path.get_ident()
                    && let Some(id) = self.lookup(&ident.to_string())
                {
                    return id;
                }
                // a named constant: differentiated as a constant, emitted as written
                let name = path.path.to_token_stream().to_string().replace(' ', "");
                self.graph.symbol(&name)
            }
            Expr::Paren(inner) => self.expr(&inner.expr),
            Expr::Group(inner) => self.expr(&inner.expr),
            Expr::Block(block) => self.block(&block.block),
            Expr::Unary(unary) => match unary.op {
                UnOp::Neg(_) => {
                    let operand = self.expr(&unary.expr);
                    self.graph.neg(operand)
                }
                UnOp::Deref(_) => {
                    self.error(unary, "references are not supported: use `f64` values")
                }
                _ => self.error(
                    unary,
                    format!("this operator is not differentiable; {SUPPORTED}"),
                ),
            },
            Expr::Binary(binary) => self.binary(binary),
            Expr::MethodCall(call) => self.method(call),
            Expr::If(branch) => self.branch(branch),
            Expr::ForLoop(_) | Expr::While(_) | Expr::Loop(_) => self.error(
                expr,
                "loops are not differentiable here; unroll the loop or move it out of the function",
            ),
            Expr::Assign(_) => self.error(
                expr,
                "mutation is not supported: bind the new value with `let` instead of assigning",
            ),
            Expr::Reference(_) | Expr::RawAddr(_) => {
                self.error(expr, "references are not supported: use `f64` values")
            }
            Expr::Call(call) => {
                let hint = match &*call.func {
                    Expr::Path(path) => {
                        let name = path
                            .path
                            .segments
                            .last()
                            .map(|s| s.ident.to_string())
                            .unwrap_or_default();
                        if Unary::from_name(&name).is_some() || Binary::from_name(&name).is_some() {
                            format!("; write it as a method: `x.{name}(…)`")
                        } else {
                            format!(
                                "; `{name}` is unknown to #[derivatives]: write its body out, or give it its own #[derivatives] and chain the derivatives by hand"
                            )
                        }
                    }
                    _ => String::new(),
                };
                self.error(
                    call,
                    format!("function calls are not differentiable here{hint}"),
                )
            }
            Expr::Return(_) => self.error(
                expr,
                "`return` is not supported; end the function with its value as the tail expression",
            ),
            Expr::Macro(_) => self.error(
                expr,
                "macros are not expanded by #[derivatives]; write the expression out",
            ),
            Expr::Match(_) => self.error(
                expr,
                "`match` is not supported; use `if`/`else` on comparisons",
            ),
            Expr::Cast(_) => self.error(
                expr,
                "casts are not supported; every value is already `f64`",
            ),
            _ => self.error(
                expr,
                format!("this construct is not supported by #[derivatives]; {SUPPORTED}"),
            ),
        }
    }

    fn binary(&mut self, binary: &syn::ExprBinary) -> Id {
        let op = match binary.op {
            BinOp::Add(_) => Binary::Add,
            BinOp::Sub(_) => Binary::Sub,
            BinOp::Mul(_) => Binary::Mul,
            BinOp::Div(_) => Binary::Div,
            BinOp::Lt(_)
            | BinOp::Le(_)
            | BinOp::Gt(_)
            | BinOp::Ge(_)
            | BinOp::Eq(_)
            | BinOp::Ne(_) => {
                return self.error(
                    binary,
                    "comparisons are supported only as the condition of an `if`",
                );
            }
            _ if is_mutation(&Expr::Binary(binary.clone())) => {
                return self.error(
                    binary,
                    "mutation is not supported: bind the new value with `let` instead of assigning",
                );
            }
            _ => {
                return self.error(
                    binary.op,
                    format!("this operator is not differentiable; {SUPPORTED}"),
                );
            }
        };
        let (left, right) = (self.expr(&binary.left), self.expr(&binary.right));
        self.graph.binary(op, left, right)
    }

    fn method(&mut self, call: &syn::ExprMethodCall) -> Id {
        let name = call.method.to_string();
        if let Some(turbofish) = &call.turbofish {
            return self.error(turbofish, "type arguments are not supported here");
        }
        let receiver = self.expr(&call.receiver);
        let arity = match name.as_str() {
            "powi" | "powf" | "atan2" | "hypot" => 1,
            _ => 0,
        };
        if call.args.len() != arity
            && (Unary::from_name(&name).is_some() || arity == 1 || name == "recip")
        {
            return self.error(call, format!("`{name}` takes {arity} argument(s)"));
        }
        match name.as_str() {
            "neg" => self.error(&call.method, "write `-x` for negation"),
            "recip" => {
                let one = self.graph.number(1.0);
                self.graph.div(one, receiver)
            }
            "powi" => match integer(&call.args[0]) {
                Some(n) => self.graph.powi(receiver, n),
                None => self.error(&call.args[0], "`powi` needs an integer literal exponent (`x.powi(3)`); use `powf` for other exponents"),
            },
            "powf" | "atan2" | "hypot" => {
                let argument = self.expr(&call.args[0]);
                let op = Binary::from_name(&name).expect("a binary primitive");
                self.graph.binary(op, receiver, argument)
            }
            _ => match Unary::from_name(&name) {
                Some(op) => self.graph.unary(op, receiver),
                None => self.error(&call.method, format!("method `{name}` is not differentiable here; the supported methods are {METHODS}")),
            },
        }
    }

    fn branch(&mut self, branch: &syn::ExprIf) -> Id {
        let comparison = match &*branch.cond {
            Expr::Binary(binary) => match binary.op {
                BinOp::Lt(_) => Some(Comparison::Less),
                BinOp::Le(_) => Some(Comparison::LessEqual),
                BinOp::Gt(_) => Some(Comparison::Greater),
                BinOp::Ge(_) => Some(Comparison::GreaterEqual),
                BinOp::Eq(_) => Some(Comparison::Equal),
                BinOp::Ne(_) => Some(Comparison::NotEqual),
                _ => None,
            }
            .map(|cmp| (cmp, binary)),
            _ => None,
        };
        let Some((cmp, binary)) = comparison else {
            return self.error(
                &branch.cond,
                "the condition must be one comparison of two f64 expressions (`a < b`)",
            );
        };
        let (a, b) = (self.expr(&binary.left), self.expr(&binary.right));
        let then = self.block(&branch.then_branch);
        let Some((_, otherwise)) = &branch.else_branch else {
            return self.error(
                branch,
                "an `if` needs an `else`: both branches give the value",
            );
        };
        let otherwise = self.expr(otherwise);
        self.graph.select(cmp, a, b, then, otherwise)
    }
}

fn is_mutation(expr: &Expr) -> bool {
    match expr {
        Expr::Assign(_) => true,
        Expr::Binary(binary) => matches!(
            binary.op,
            BinOp::AddAssign(_)
                | BinOp::SubAssign(_)
                | BinOp::MulAssign(_)
                | BinOp::DivAssign(_)
                | BinOp::RemAssign(_)
                | BinOp::BitXorAssign(_)
                | BinOp::BitAndAssign(_)
                | BinOp::BitOrAssign(_)
                | BinOp::ShlAssign(_)
                | BinOp::ShrAssign(_)
        ),
        _ => false,
    }
}

/// The value of an integer literal, possibly negated (`3`, `-2`).
fn integer(expr: &Expr) -> Option<i32> {
    match expr {
        Expr::Lit(syn::ExprLit {
            lit: Lit::Int(int), ..
        }) => int.base10_parse().ok(),
        Expr::Unary(syn::ExprUnary {
            op: UnOp::Neg(_),
            expr,
            ..
        }) => integer(expr).and_then(i32::checked_neg),
        Expr::Paren(inner) => integer(&inner.expr),
        _ => None,
    }
}

/// Lowers `function` into the IR.
pub fn lower(function: &ItemFn) -> syn::Result<Lowered> {
    let mut lowering = Lowering {
        graph: Graph::new(),
        scopes: vec![HashMap::new()],
        errors: None,
        error_count: 0,
    };
    let parameters = lowering.parameters(function);
    let value = lowering.block(&function.block);
    match lowering.errors {
        Some(errors) => Err(errors),
        None => Ok(Lowered {
            graph: lowering.graph,
            value,
            parameters,
        }),
    }
}
