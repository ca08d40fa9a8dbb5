//! The import graph of a crate's modules, and its circles (issue 23: "no import circle of
//! more than two modules in any crate").
//!
//! **Nodes** are file-level modules: every `.rs` file reached from the crate root by `mod`
//! declarations (an inline `mod tests { … }` belongs to the file it is written in). A
//! module is named by its path from the root (`geometry::solver`; the root is `crate`).
//!
//! **Edges.** A → B when A's code names an item *defined* in B:
//! - a private `use` (an unused import is a warning, so a private import is a use), a `use`
//!   inside a function, or a path in code — `crate::…`, `super::…`, `self::…`, a child
//!   module's name, or a name a `use` brought into scope, followed by `::` — including paths
//!   in macro invocations (`format!`, `$crate::…` in `macro_rules!`);
//! - each path is resolved through `use` and `pub use` re-exports (and globs) to the module
//!   that defines its first item (a struct, enum, fn, trait, const, static, type alias or
//!   `macro_rules!`), so `crate::Error` is an edge to `error`, not to the root.
//!
//! **Not edges**: `mod` declarations and `pub use` / `pub(crate) use` re-exports. A parent
//! that declares its children and re-exports their items is the module tree, not a
//! dependency on them: a child naming its parent's items, with the parent re-exporting the
//! child's, is no circle. A re-exported name that the module's own code also names *is* an
//! edge (its code uses it). Doc comments (intra-doc links) are not code and not edges.
//!
//! **Why a parse (syn) and not a text scan**: resolving a path needs each module's items,
//! imports and inline modules (`super::` inside `mod tests` is the file itself), which syn
//! gives exactly; paths inside function bodies and macro invocations are found in the
//! token stream of each item. Limits (none occur in this workspace, and the loader reports
//! a missing file): `#[path]` attributes on `mod` are not followed; a name brought in by a
//! glob of an external crate is taken as external. A method call (`x.f()`) names no path:
//! the edge is the one to the module of `x`'s type, where the code names that type.
//!
//! **Circles** are the strongly connected components of the graph with more than one
//! module (Tarjan's algorithm).

use std::collections::{BTreeMap, BTreeSet, HashSet};
use std::path::{Path, PathBuf};

use proc_macro2::{Delimiter, TokenStream, TokenTree};
use quote::ToTokens;
use syn::parse::Parser;
use syn::punctuated::Punctuated;
use syn::{Item, UseTree, Visibility};

/// A name imported by `use`: `use a::b::c as d;` is `d` → `[a, b, c]`.
struct Import {
    name: String,
    path: Vec<String>,
    public: bool,
}

/// A module: file-level or inline.
struct Module {
    /// The path from the crate root (`crate` for the root).
    name: String,
    /// The file-level module this module is written in (itself for a file).
    file: usize,
    parent: Option<usize>,
    children: BTreeMap<String, usize>,
    items: HashSet<String>,
    imports: Vec<Import>,
    /// Glob imports (`use a::b::*`): the path and whether it is a re-export.
    globs: Vec<(Vec<String>, bool)>,
    /// Paths of two or more segments named in code (including `use` inside functions).
    paths: Vec<Vec<String>>,
    /// Every identifier in the module's code outside its `use` items.
    idents: HashSet<String>,
}

/// The modules of one crate and the edges between its files.
pub struct ImportGraph {
    modules: Vec<Module>,
}

/// Where resolving a path ends.
enum Target {
    /// A module (the path names it, or an item of it that was not found: an enum's
    /// variant, an associated item).
    Module(usize),
    /// An item defined in this module.
    Item(usize),
}

impl Target {
    fn module(&self) -> usize {
        match *self {
            Target::Module(m) | Target::Item(m) => m,
        }
    }
}

fn is_public(vis: &Visibility) -> bool {
    !matches!(vis, Visibility::Inherited)
}

/// The leaves of a use tree: `(name, path, glob)`; a glob's name is empty.
fn use_leaves(tree: &UseTree, prefix: &mut Vec<String>, out: &mut Vec<(String, Vec<String>)>) {
    match tree {
        UseTree::Path(p) => {
            prefix.push(p.ident.to_string());
            use_leaves(&p.tree, prefix, out);
            prefix.pop();
        }
        UseTree::Name(n) if n.ident == "self" => {
            let name = prefix.last().cloned().unwrap_or_default();
            out.push((name, prefix.clone()));
        }
        UseTree::Name(n) => {
            let mut path = prefix.clone();
            path.push(n.ident.to_string());
            out.push((n.ident.to_string(), path));
        }
        UseTree::Rename(r) => {
            let mut path = prefix.clone();
            path.push(r.ident.to_string());
            out.push((r.rename.to_string(), path));
        }
        UseTree::Glob(_) => out.push((String::new(), prefix.clone())),
        UseTree::Group(g) => {
            for tree in &g.items {
                use_leaves(tree, prefix, out);
            }
        }
    }
}

/// Paths in a token stream: runs `a::b::c` (not after a leading `::`), with `a::{b, c::d}`
/// expanded; every identifier goes into `idents`.
fn scan_tokens(tokens: TokenStream, paths: &mut Vec<Vec<String>>, idents: &mut HashSet<String>) {
    let tokens: Vec<TokenTree> = tokens.into_iter().collect();
    let colons = |i: usize| {
        matches!((tokens.get(i), tokens.get(i + 1)),
            (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b)))
                if a.as_char() == ':' && b.as_char() == ':' && a.spacing() == proc_macro2::Spacing::Joint)
    };
    let mut i = 0;
    while i < tokens.len() {
        match &tokens[i] {
            TokenTree::Group(g) => {
                scan_tokens(g.stream(), paths, idents);
                i += 1;
            }
            TokenTree::Ident(first) => {
                let absolute = i >= 2 && colons(i - 2);
                let mut run = vec![first.to_string()];
                idents.insert(first.to_string());
                let mut j = i + 1;
                while colons(j) {
                    match tokens.get(j + 2) {
                        Some(TokenTree::Ident(next)) => {
                            idents.insert(next.to_string());
                            run.push(next.to_string());
                            j += 3;
                        }
                        Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Brace => {
                            let parser = Punctuated::<UseTree, syn::Token![,]>::parse_terminated;
                            if let (false, Ok(trees)) = (absolute, parser.parse2(g.stream())) {
                                let mut leaves = Vec::new();
                                for tree in &trees {
                                    use_leaves(tree, &mut run.clone(), &mut leaves);
                                }
                                paths.extend(leaves.into_iter().map(|(_, p)| p));
                            }
                            scan_tokens(g.stream(), &mut Vec::new(), idents);
                            run.clear();
                            j += 3;
                            break;
                        }
                        _ => break,
                    }
                }
                if !absolute && run.len() > 1 {
                    paths.push(run);
                }
                i = j;
            }
            TokenTree::Punct(_) | TokenTree::Literal(_) => i += 1,
        }
    }
}

impl ImportGraph {
    /// The import graph of the crate whose root file is `root` (`src/lib.rs`), reading files
    /// with `read` (`None`: no such file). Errors name the file that does not parse or the
    /// module whose file is missing.
    pub fn load(root: &Path, read: &dyn Fn(&Path) -> Option<String>) -> Result<Self, String> {
        let mut graph = ImportGraph {
            modules: Vec::new(),
        };
        let dir = root.parent().unwrap_or(Path::new("")).to_path_buf();
        graph.load_file(root, "crate".to_owned(), None, dir, read)?;
        Ok(graph)
    }

    /// The import graph of a crate on disk.
    pub fn from_disk(root: &Path) -> Result<Self, String> {
        Self::load(root, &|path| std::fs::read_to_string(path).ok())
    }

    fn new_module(&mut self, name: String, parent: Option<usize>, file: Option<usize>) -> usize {
        let id = self.modules.len();
        self.modules.push(Module {
            name,
            file: file.unwrap_or(id),
            parent,
            children: BTreeMap::new(),
            items: HashSet::new(),
            imports: Vec::new(),
            globs: Vec::new(),
            paths: Vec::new(),
            idents: HashSet::new(),
        });
        if let Some(parent) = parent {
            let short = self.modules[id]
                .name
                .rsplit("::")
                .next()
                .unwrap_or("")
                .to_owned();
            self.modules[parent].children.insert(short, id);
        }
        id
    }

    fn load_file(
        &mut self,
        file: &Path,
        name: String,
        parent: Option<usize>,
        dir: PathBuf,
        read: &dyn Fn(&Path) -> Option<String>,
    ) -> Result<(), String> {
        let text = read(file).ok_or_else(|| format!("{}: cannot read", file.display()))?;
        let parsed = syn::parse_file(&text).map_err(|e| format!("{}: {e}", file.display()))?;
        let id = self.new_module(name, parent, None);
        self.add_items(id, parsed.items, &dir, read)
    }

    fn add_items(
        &mut self,
        id: usize,
        items: Vec<Item>,
        dir: &Path,
        read: &dyn Fn(&Path) -> Option<String>,
    ) -> Result<(), String> {
        for item in items {
            let defined = match &item {
                Item::Const(i) => Some(&i.ident),
                Item::Enum(i) => Some(&i.ident),
                Item::ExternCrate(i) => Some(i.rename.as_ref().map_or(&i.ident, |r| &r.1)),
                Item::Fn(i) => Some(&i.sig.ident),
                Item::Macro(i) => i.ident.as_ref(),
                Item::Static(i) => Some(&i.ident),
                Item::Struct(i) => Some(&i.ident),
                Item::Trait(i) => Some(&i.ident),
                Item::TraitAlias(i) => Some(&i.ident),
                Item::Type(i) => Some(&i.ident),
                Item::Union(i) => Some(&i.ident),
                _ => None,
            };
            if let Some(ident) = defined {
                self.modules[id].items.insert(ident.to_string());
            }
            match item {
                Item::Mod(m) => {
                    let name = match self.modules[id].name.as_str() {
                        "crate" => m.ident.to_string(),
                        parent => format!("{parent}::{}", m.ident),
                    };
                    let child_dir = dir.join(m.ident.to_string());
                    match m.content {
                        Some((_, items)) => {
                            let file = self.modules[id].file;
                            let child = self.new_module(name, Some(id), Some(file));
                            self.add_items(child, items, &child_dir, read)?;
                        }
                        None => {
                            let flat = dir.join(format!("{}.rs", m.ident));
                            let nested = child_dir.join("mod.rs");
                            let file = if read(&flat).is_some() { flat } else { nested };
                            self.load_file(&file, name, Some(id), child_dir, read)?;
                        }
                    }
                }
                Item::Use(u) => {
                    let mut leaves = Vec::new();
                    use_leaves(&u.tree, &mut Vec::new(), &mut leaves);
                    let public = is_public(&u.vis);
                    for (name, path) in leaves {
                        if name.is_empty() {
                            self.modules[id].globs.push((path, public));
                        } else {
                            self.modules[id].imports.push(Import { name, path, public });
                        }
                    }
                }
                other => {
                    let module = &mut self.modules[id];
                    scan_tokens(
                        other.to_token_stream(),
                        &mut module.paths,
                        &mut module.idents,
                    );
                }
            }
        }
        Ok(())
    }

    /// A name in the scope of module `m`: a child module, an item, an import, or a name a
    /// glob brings in.
    fn lookup(&self, m: usize, name: &str, depth: usize) -> Option<Target> {
        let module = &self.modules[m];
        if let Some(&child) = module.children.get(name) {
            return Some(Target::Module(child));
        }
        if module.items.contains(name) {
            return Some(Target::Item(m));
        }
        if let Some(import) = module.imports.iter().find(|i| i.name == name) {
            return self.resolve(m, &import.path, depth + 1);
        }
        for (glob, _) in &module.globs {
            if let Some(Target::Module(g)) = self.resolve(m, glob, depth + 1)
                && g != m
                && let Some(found) = self.lookup(g, name, depth + 1)
            {
                return Some(found);
            }
        }
        None
    }

    /// Whether module `m` imports `name` from outside the crate.
    fn imports_from_outside(&self, m: usize, name: &str, depth: usize) -> bool {
        (self.modules[m].imports.iter())
            .any(|i| i.name == name && self.resolve(m, &i.path, depth + 1).is_none())
    }

    /// Where `path`, written in module `m`, leads (`None`: outside the crate).
    fn resolve(&self, m: usize, path: &[String], depth: usize) -> Option<Target> {
        if depth > 32 || path.is_empty() {
            return None;
        }
        let (mut at, mut rest) = match path[0].as_str() {
            "crate" => (0, &path[1..]),
            "self" => (m, &path[1..]),
            "super" => {
                let mut at = m;
                let mut rest = path;
                while rest.first().map(String::as_str) == Some("super") {
                    at = self.modules[at].parent?;
                    rest = &rest[1..];
                }
                (at, rest)
            }
            name => match self.lookup(m, name, depth)? {
                Target::Item(defining) => return Some(Target::Item(defining)),
                Target::Module(module) => (module, &path[1..]),
            },
        };
        while let Some(name) = rest.first() {
            match self.lookup(at, name, depth) {
                Some(Target::Module(module)) => at = module,
                Some(Target::Item(defining)) => return Some(Target::Item(defining)),
                // A name the module imports from another crate (`pub use other::units;`):
                // the path leads outside the crate, not to the module that re-exports it.
                None if self.imports_from_outside(at, name, depth) => return None,
                None => break,
            }
            rest = &rest[1..];
        }
        Some(Target::Module(at))
    }

    /// The edges between file-level modules, as indices (no self-edges).
    fn edges(&self) -> BTreeSet<(usize, usize)> {
        let mut edges = BTreeSet::new();
        for (m, module) in self.modules.iter().enumerate() {
            let used_imports = module
                .imports
                .iter()
                .filter(|i| !i.public || module.idents.contains(&i.name))
                .map(|i| &i.path);
            let private_globs = module.globs.iter().filter(|(_, public)| !public);
            let named = used_imports
                .chain(private_globs.map(|(path, _)| path))
                .chain(&module.paths);
            for path in named {
                if let Some(target) = self.resolve(m, path, 0) {
                    let to = self.modules[target.module()].file;
                    if to != module.file {
                        edges.insert((module.file, to));
                    }
                }
            }
        }
        edges
    }

    /// The edges between file-level modules, by name (`from → to`).
    pub fn named_edges(&self) -> Vec<(String, String)> {
        let name = |m: usize| self.modules[m].name.clone();
        self.edges()
            .into_iter()
            .map(|(a, b)| (name(a), name(b)))
            .collect()
    }

    /// The circles: strongly connected components of more than one module, each sorted by
    /// name, the largest first.
    pub fn circles(&self) -> Vec<Vec<String>> {
        let n = self.modules.len();
        let mut next = vec![Vec::new(); n];
        for (a, b) in self.edges() {
            next[a].push(b);
        }
        let mut tarjan = Tarjan {
            next: &next,
            index: vec![None; n],
            low: vec![0; n],
            stack: Vec::new(),
            on_stack: vec![false; n],
            counter: 0,
            components: Vec::new(),
        };
        for v in 0..n {
            if self.modules[v].file == v && tarjan.index[v].is_none() {
                tarjan.visit(v);
            }
        }
        let mut circles: Vec<Vec<String>> = tarjan
            .components
            .into_iter()
            .filter(|c| c.len() > 1)
            .map(|c| {
                let mut names: Vec<String> = c
                    .into_iter()
                    .map(|m| self.modules[m].name.clone())
                    .collect();
                names.sort();
                names
            })
            .collect();
        circles.sort_by(|a, b| b.len().cmp(&a.len()).then_with(|| a.cmp(b)));
        circles
    }
}

/// Tarjan's strongly connected components (recursive: module graphs are shallow).
struct Tarjan<'a> {
    next: &'a [Vec<usize>],
    index: Vec<Option<usize>>,
    low: Vec<usize>,
    stack: Vec<usize>,
    on_stack: Vec<bool>,
    counter: usize,
    components: Vec<Vec<usize>>,
}

impl Tarjan<'_> {
    fn visit(&mut self, v: usize) {
        self.index[v] = Some(self.counter);
        self.low[v] = self.counter;
        self.counter += 1;
        self.stack.push(v);
        self.on_stack[v] = true;
        for &w in &self.next[v] {
            match self.index[w] {
                None => {
                    self.visit(w);
                    self.low[v] = self.low[v].min(self.low[w]);
                }
                Some(index) if self.on_stack[w] => self.low[v] = self.low[v].min(index),
                Some(_) => {}
            }
        }
        if Some(self.low[v]) == self.index[v] {
            let mut component = Vec::new();
            while let Some(w) = self.stack.pop() {
                self.on_stack[w] = false;
                component.push(w);
                if w == v {
                    break;
                }
            }
            self.components.push(component);
        }
    }
}
