//! The shape of the source tree: no import cycle between the files of `src/`, no file there over
//! [`MAX_FILE_LINES`] lines and no function over [`MAX_FN_LINES`] lines (apart from those named
//! in [`LONG_FUNCTIONS`], each with the reason it stays whole).
//!
//! A small reader of Rust source, no parser dependency: comments and literals are blanked, then
//! every `use` declaration and every path that starts with `crate::`, `super::`, `self::` or the
//! name of a child module is resolved to the file that defines the module it names (a module is
//! a file; `mod.rs` stands for its directory; an inline `mod x { .. }` belongs to its file). A
//! path through a re-export (`pub use child::Item` in a `mod.rs`) is followed to the file the item
//! comes from, and a re-export itself is not a dependency: a `mod.rs` that only gathers its
//! children's items is their front, not their user. Code under `#[cfg(test)]` is left out of the
//! graph: a test module uses its file the way an integration test does.

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::path::Path;

/// The longest a file of `src/` may be.
const MAX_FILE_LINES: usize = 600;
/// The longest a function may be, from the line of its `fn` to its closing brace.
const MAX_FN_LINES: usize = 80;

/// The functions allowed over [`MAX_FN_LINES`]: (file, function name, why it stays whole).
const LONG_FUNCTIONS: &[(&str, &str, &str)] = &[];

/// A token of blanked source: an identifier, `::`, or one other character.
#[derive(Clone, Debug, PartialEq)]
struct Token {
    text: String,
    line: usize,
}

/// Replaces the contents of comments, string and character literals by spaces (keeping the
/// newlines, so that line numbers stay), leaving the code's own tokens.
fn blank(source: &str) -> String {
    let c: Vec<char> = source.chars().collect();
    let mut out = String::with_capacity(source.len());
    let is_ident = |ch: char| ch.is_alphanumeric() || ch == '_';
    let keep_newlines = |out: &mut String, chars: &[char]| {
        for &ch in chars {
            out.push(if ch == '\n' { '\n' } else { ' ' });
        }
    };
    let mut i = 0;
    while i < c.len() {
        // An identifier just before a quote makes it part of a byte literal (`b'x'`, `b"x"`,
        // `br"x"`) when that identifier is `b`, else of something else (`r#ident`).
        let byte_prefix = i > 0 && c[i - 1] == 'b' && (i < 2 || !is_ident(c[i - 2]));
        let prev_ident = i > 0 && is_ident(c[i - 1]) && !byte_prefix;
        if c[i] == '/' && c.get(i + 1) == Some(&'/') {
            let end = (i..c.len()).find(|&j| c[j] == '\n').unwrap_or(c.len());
            keep_newlines(&mut out, &c[i..end]);
            i = end;
        } else if c[i] == '/' && c.get(i + 1) == Some(&'*') {
            let (mut depth, mut j) = (1, i + 2);
            while j < c.len() && depth > 0 {
                if c[j] == '/' && c.get(j + 1) == Some(&'*') {
                    depth += 1;
                    j += 2;
                } else if c[j] == '*' && c.get(j + 1) == Some(&'/') {
                    depth -= 1;
                    j += 2;
                } else {
                    j += 1;
                }
            }
            keep_newlines(&mut out, &c[i..j.min(c.len())]);
            i = j;
        } else if let Some(end) = raw_string_end(&c, i).filter(|_| !prev_ident) {
            keep_newlines(&mut out, &c[i..end]);
            i = end;
        } else if c[i] == '"' {
            let mut j = i + 1;
            while j < c.len() && c[j] != '"' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            out.push('"');
            keep_newlines(&mut out, &c[i + 1..j.min(c.len())]);
            out.push('"');
            i = j + 1;
        } else if c[i] == '\'' && !prev_ident {
            // A character literal ('x', '\n', '\u{..}') or a lifetime ('a, left as it is).
            let end = if c.get(i + 1) == Some(&'\\') {
                (i + 2..c.len()).find(|&j| c[j] == '\'').map(|j| j + 1)
            } else if c.get(i + 2) == Some(&'\'') {
                Some(i + 3)
            } else {
                None
            };
            match end {
                Some(end) => {
                    out.push_str("' '");
                    i = end;
                }
                None => {
                    out.push('\'');
                    i += 1;
                }
            }
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// Where the raw string literal (`r"..."`, `r#"..."#`, ...) starting at `i` ends, if one does.
fn raw_string_end(c: &[char], i: usize) -> Option<usize> {
    if c[i] != 'r' {
        return None;
    }
    let hashes = c[i + 1..].iter().take_while(|&&ch| ch == '#').count();
    if c.get(i + 1 + hashes) != Some(&'"') {
        return None;
    }
    let mut j = i + 2 + hashes;
    while j < c.len() {
        if c[j] == '"'
            && c[j + 1..]
                .iter()
                .take(hashes)
                .filter(|&&ch| ch == '#')
                .count()
                == hashes
        {
            return Some(j + 1 + hashes);
        }
        j += 1;
    }
    Some(c.len())
}

/// The tokens of blanked source: identifiers (and numbers), `::`, and single characters.
fn tokens(blanked: &str) -> Vec<Token> {
    let c: Vec<char> = blanked.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < c.len() {
        if c[i] == '\n' {
            line += 1;
            i += 1;
        } else if c[i].is_whitespace() {
            i += 1;
        } else if c[i].is_alphanumeric() || c[i] == '_' {
            let start = i;
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                i += 1;
            }
            out.push(Token {
                text: c[start..i].iter().collect(),
                line,
            });
        } else if c[i] == ':' && c.get(i + 1) == Some(&':') {
            out.push(Token {
                text: "::".into(),
                line,
            });
            i += 2;
        } else {
            out.push(Token {
                text: c[i].to_string(),
                line,
            });
            i += 1;
        }
    }
    out
}

/// A module's path from the crate root, as segments (the root is empty).
type ModulePath = Vec<String>;

/// The module path of a file of `src/`, from its path relative to `src/`.
fn module_of(relative: &str) -> ModulePath {
    let stem = relative.trim_end_matches(".rs");
    let mut segments: ModulePath = stem.split('/').map(str::to_string).collect();
    if matches!(
        segments.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        segments.pop();
    }
    segments
}

/// One name a `use` declaration binds: the path it names (relative to the module it is written
/// in) and the name it is bound to (`*` for a glob).
#[derive(Clone, Debug)]
struct Binding {
    path: Vec<String>,
    name: String,
}

/// A path the code names: the module it is written in, its segments, its line, whether it is
/// in a `pub use` (a re-export of the module's own children is no dependency) and whether it is
/// under `#[cfg(test)]` (no dependency either).
#[derive(Clone, Debug)]
struct Reference {
    module: ModulePath,
    path: Vec<String>,
    line: usize,
    reexport: bool,
    test: bool,
}

/// What reading one file gives.
#[derive(Default, Debug)]
struct FileFacts {
    /// Inline modules (with their path from the crate root).
    inline_modules: Vec<ModulePath>,
    /// Per module written in this file, the names its `use` declarations bind.
    bindings: Vec<(ModulePath, Binding)>,
    /// Per module written in this file, the items it defines.
    items: Vec<(ModulePath, String)>,
    references: Vec<Reference>,
    /// Functions with a body: name, first line, last line.
    functions: Vec<(String, usize, usize)>,
    lines: usize,
}

/// The index of the token closing the bracket that opens at `open`.
fn matching(tokens: &[Token], open: usize) -> usize {
    let (opening, closing) = match tokens[open].text.as_str() {
        "{" => ("{", "}"),
        "(" => ("(", ")"),
        _ => ("[", "]"),
    };
    let mut depth = 0;
    for (j, t) in tokens.iter().enumerate().skip(open) {
        if t.text == opening {
            depth += 1;
        } else if t.text == closing {
            depth -= 1;
            if depth == 0 {
                return j;
            }
        }
    }
    tokens.len() - 1
}

/// The index of the token that ends the item starting at `start`: its first `;` outside
/// brackets, or the brace closing its first block.
fn item_end(tokens: &[Token], start: usize) -> usize {
    let mut j = start;
    while j < tokens.len() {
        match tokens[j].text.as_str() {
            ";" => return j,
            "{" => return matching(tokens, j),
            "(" | "[" => j = matching(tokens, j) + 1,
            _ => j += 1,
        }
    }
    tokens.len() - 1
}

fn is_ident(text: &str) -> bool {
    text.chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
}

/// Expands the use tree starting at `i` (after `use`) under `prefix` into bindings; returns
/// the index after the tree.
fn use_tree(tokens: &[Token], mut i: usize, prefix: &[String], out: &mut Vec<Binding>) -> usize {
    let mut path = prefix.to_vec();
    if tokens[i].text == "::" {
        i += 1;
    }
    loop {
        let text = tokens[i].text.as_str();
        if text == "{" {
            let close = matching(tokens, i);
            i += 1;
            while i < close {
                i = use_tree(tokens, i, &path, out);
                if tokens[i].text == "," {
                    i += 1;
                }
            }
            return close + 1;
        }
        if text == "*" {
            out.push(Binding {
                path,
                name: "*".into(),
            });
            return i + 1;
        }
        if text == "self" && !path.is_empty() && i > 0 && tokens[i - 1].text != "::" {
            // `a::{self, ..}` binds `a`.
            let name = path.last().unwrap().clone();
            return finish_binding(tokens, i + 1, path, name, out);
        }
        path.push(text.to_string());
        i += 1;
        if tokens[i].text == "::" {
            i += 1;
        } else {
            let name = path.last().unwrap().clone();
            return finish_binding(tokens, i, path, name, out);
        }
    }
}

/// Records the binding of `path` (renamed by a following `as name`); returns the index after it.
fn finish_binding(
    tokens: &[Token],
    mut i: usize,
    path: Vec<String>,
    mut name: String,
    out: &mut Vec<Binding>,
) -> usize {
    if tokens[i].text == "as" {
        name = tokens[i + 1].text.clone();
        i += 2;
    }
    out.push(Binding { path, name });
    i
}

/// Whether the `use` at `i` is public in some way (`pub`, `pub(crate)`, `pub(super)`, ...).
fn is_reexport(tokens: &[Token], i: usize) -> bool {
    if i >= 1 && tokens[i - 1].text == "pub" {
        return true;
    }
    i >= 2 && tokens[i - 1].text == ")" && {
        let open = (0..i - 1).rev().find(|&j| tokens[j].text == "(");
        open.is_some_and(|j| j >= 1 && tokens[j - 1].text == "pub")
    }
}

/// Marks, per token, whether it lies in an item under `#[cfg(test)]`.
fn test_only(tokens: &[Token]) -> Vec<bool> {
    let mut marked = vec![false; tokens.len()];
    let texts: Vec<&str> = tokens.iter().map(|t| t.text.as_str()).collect();
    for i in 0..tokens.len() {
        if texts[i..].starts_with(&["#", "[", "cfg", "(", "test", ")", "]"]) {
            let end = item_end(tokens, i + 7);
            marked[i..=end].iter_mut().for_each(|m| *m = true);
        }
    }
    marked
}

/// The identifiers the file's code uses outside `use` declarations and `#[cfg(test)]` items.
fn used_names<'a>(tokens: &'a [Token], test: &[bool]) -> HashSet<&'a str> {
    let mut used = HashSet::new();
    let mut i = 0;
    while i < tokens.len() {
        if tokens[i].text == "use" && (i == 0 || tokens[i - 1].text != "::") {
            i = item_end(tokens, i) + 1;
            continue;
        }
        if tokens[i].text == "mod" {
            i += 2; // A module's declaration is no use of its name.
            continue;
        }
        if !test[i] && is_ident(&tokens[i].text) {
            used.insert(tokens[i].text.as_str());
        }
        i += 1;
    }
    used
}

const ITEM_KEYWORDS: &[&str] = &[
    "fn", "struct", "enum", "trait", "type", "const", "static", "union", "mod",
];

/// Reads one file of module `module`; `children` tells which names are child modules of a
/// module (for paths such as `child::item`).
fn read_file(
    source: &str,
    module: &ModulePath,
    children: &dyn Fn(&ModulePath, &str) -> bool,
) -> FileFacts {
    let tokens = tokens(&blank(source));
    let test = test_only(&tokens);
    let mut reader = Reader {
        used: used_names(&tokens, &test),
        tokens: &tokens,
        test,
        children,
        facts: FileFacts {
            lines: source.lines().count(),
            ..FileFacts::default()
        },
    };
    // Inline modules open: (path, index of their closing brace).
    let mut open: Vec<(ModulePath, usize)> = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        while open.last().is_some_and(|(_, close)| i > *close) {
            open.pop();
        }
        let current = open.last().map_or(module, |(path, _)| path).clone();
        let (text, next) = (tokens[i].text.as_str(), reader.text(i + 1));
        let prev = if i > 0 { reader.text(i - 1) } else { "" };
        reader.item(i, &current);
        if text == "mod" && is_ident(next) && reader.text(i + 2) == "{" {
            let mut path = current.clone();
            path.push(next.to_string());
            reader.facts.inline_modules.push(path.clone());
            open.push((path, matching(&tokens, i + 2)));
            i += 3;
        } else if text == "use" && prev != "::" {
            i = reader.use_declaration(i, &current);
        } else if reader.starts_path(i, &current) && prev != "::" {
            i = reader.path(i, current);
        } else {
            i += 1;
        }
    }
    reader.facts
}

/// The state of [`read_file`].
struct Reader<'a> {
    tokens: &'a [Token],
    /// Per token, whether it is under `#[cfg(test)]`.
    test: Vec<bool>,
    used: HashSet<&'a str>,
    children: &'a dyn Fn(&ModulePath, &str) -> bool,
    facts: FileFacts,
}

impl<'a> Reader<'a> {
    /// The text of token `i` (empty past the end).
    fn text(&self, i: usize) -> &'a str {
        self.tokens.get(i).map_or("", |t| t.text.as_str())
    }

    /// Records the item token `i` declares in module `current` (its name, and for a function
    /// with a body its lines).
    fn item(&mut self, i: usize, current: &ModulePath) {
        let (text, next) = (self.text(i), self.text(i + 1));
        let prev = if i > 0 { self.text(i - 1) } else { "" };
        if ITEM_KEYWORDS.contains(&text) && is_ident(next) && prev != "::" {
            let name = next.to_string();
            self.facts.items.push((current.clone(), name));
        }
        if text == "macro_rules" && next == "!" {
            let name = self.text(i + 2).to_string();
            self.facts.items.push((current.clone(), name));
        }
        if text == "fn" && is_ident(next) {
            let end = item_end(self.tokens, i + 2);
            if self.tokens[end].text == "}" {
                let (first, last) = (self.tokens[i].line, self.tokens[end].line);
                let name = next.to_string();
                self.facts.functions.push((name, first, last));
            }
        }
    }

    /// Whether the path at token `i` is one the reader follows: it starts with `crate`,
    /// `super`, `self` or a child module of `current`.
    fn starts_path(&self, i: usize, current: &ModulePath) -> bool {
        let text = self.text(i);
        let first = matches!(text, "crate" | "super" | "self") || (self.children)(current, text);
        first && self.text(i + 1) == "::"
    }

    /// Reads the `use` declaration at token `i` of module `current`; returns the index after
    /// it.
    fn use_declaration(&mut self, i: usize, current: &ModulePath) -> usize {
        let mut bound = Vec::new();
        let end = use_tree(self.tokens, i + 1, &[], &mut bound);
        for binding in bound {
            // A re-export the file's own code also uses is a dependency all the same.
            let reexport =
                is_reexport(self.tokens, i) && !self.used.contains(binding.name.as_str());
            let first = binding.path[0].as_str();
            if matches!(first, "crate" | "super" | "self") || (self.children)(current, first) {
                self.facts.references.push(Reference {
                    module: current.clone(),
                    path: binding.path.clone(),
                    line: self.tokens[i].line,
                    reexport,
                    test: self.test[i],
                });
            }
            self.facts.bindings.push((current.clone(), binding));
        }
        end
    }

    /// Reads the path starting at token `i` in the code of module `current`; returns the index
    /// after it.
    fn path(&mut self, i: usize, current: ModulePath) -> usize {
        let mut path = vec![self.tokens[i].text.clone()];
        let mut j = i + 1;
        while self.text(j) == "::" && is_ident(self.text(j + 1)) {
            path.push(self.tokens[j + 1].text.clone());
            j += 2;
        }
        self.facts.references.push(Reference {
            module: current,
            path,
            line: self.tokens[i].line,
            reexport: false,
            test: self.test[i],
        });
        j
    }
}

/// The crate as read: its files and modules, and what each module binds and defines.
struct Crate {
    /// Paths of the files, relative to the package root (`src/...`).
    files: Vec<String>,
    facts: Vec<FileFacts>,
    /// Every module (file or inline) with the index of its file.
    modules: HashMap<ModulePath, usize>,
    bindings: HashMap<ModulePath, Vec<Binding>>,
    items: HashMap<ModulePath, HashSet<String>>,
}

impl Crate {
    /// Reads `sources`: (path relative to `src/`, text).
    fn read(sources: &[(String, String)]) -> Crate {
        let mut modules: HashMap<ModulePath, usize> = HashMap::new();
        for (f, (relative, _)) in sources.iter().enumerate() {
            modules.insert(module_of(relative), f);
        }
        let file_modules = modules.clone();
        let children = |parent: &ModulePath, name: &str| {
            let mut path = parent.clone();
            path.push(name.to_string());
            file_modules.contains_key(&path)
        };
        let facts: Vec<FileFacts> = sources
            .iter()
            .map(|(relative, text)| read_file(text, &module_of(relative), &children))
            .collect();
        let (mut bindings, mut items) = (HashMap::new(), HashMap::new());
        for (f, file) in facts.iter().enumerate() {
            for path in &file.inline_modules {
                modules.insert(path.clone(), f);
            }
            for (module, binding) in &file.bindings {
                let list: &mut Vec<Binding> = bindings.entry(module.clone()).or_default();
                list.push(binding.clone());
            }
            for (module, item) in &file.items {
                let set: &mut HashSet<String> = items.entry(module.clone()).or_default();
                set.insert(item.clone());
            }
        }
        Crate {
            files: sources.iter().map(|(r, _)| format!("src/{r}")).collect(),
            facts,
            modules,
            bindings,
            items,
        }
    }

    /// The file that defines what `path`, written in module `from`, names; `None` for a path
    /// that leaves the crate (or that the reader cannot follow).
    fn resolve(&self, from: &ModulePath, path: &[String], depth: usize) -> Option<usize> {
        if depth > 16 {
            return None;
        }
        let mut module = from.clone();
        let mut i = 0;
        while i < path.len() {
            match path[i].as_str() {
                "crate" => module.clear(),
                "super" => {
                    module.pop()?;
                }
                "self" => {}
                _ => break,
            }
            i += 1;
        }
        if i == 0
            && !self
                .modules
                .contains_key(&[&module[..], &path[..1]].concat())
        {
            // Neither `crate`, `super`, `self` nor a child module: another crate (or a name
            // of the prelude).
            return None;
        }
        while i < path.len() {
            let mut deeper = module.clone();
            deeper.push(path[i].clone());
            if !self.modules.contains_key(&deeper) {
                break;
            }
            module = deeper;
            i += 1;
        }
        match path.get(i) {
            Some(item) if item != "*" => self.item_file(&module, item, depth),
            _ => self.modules.get(&module).copied(),
        }
    }

    /// The file that defines `item` as module `module` sees it: its own definition, else the
    /// file its `use` of that name leads to, else one of its glob imports that has it.
    fn item_file(&self, module: &ModulePath, item: &str, depth: usize) -> Option<usize> {
        let own = self.modules.get(module).copied();
        if self.items.get(module).is_some_and(|s| s.contains(item)) {
            return own;
        }
        let bindings = self.bindings.get(module).map_or(&[][..], Vec::as_slice);
        if let Some(b) = bindings.iter().find(|b| b.name == item) {
            return self.resolve(module, &b.path, depth + 1);
        }
        for glob in bindings.iter().filter(|b| b.name == "*") {
            let Some(target) = self.glob_module(module, &glob.path) else {
                continue;
            };
            if self.items.get(&target).is_some_and(|s| s.contains(item))
                || self
                    .bindings
                    .get(&target)
                    .is_some_and(|l| l.iter().any(|b| b.name == item))
            {
                return self.item_file(&target, item, depth + 1);
            }
        }
        own
    }

    /// The module a glob import `path::*` written in `from` opens.
    fn glob_module(&self, from: &ModulePath, path: &[String]) -> Option<ModulePath> {
        let mut module = from.clone();
        for segment in path {
            match segment.as_str() {
                "crate" => module.clear(),
                "super" => {
                    module.pop()?;
                }
                "self" => {}
                name => module.push(name.to_string()),
            }
        }
        self.modules.contains_key(&module).then_some(module)
    }

    /// The dependencies between files: (from, to) with the first line of `from` that makes it.
    fn edges(&self) -> BTreeMap<(usize, usize), usize> {
        let mut edges = BTreeMap::new();
        for (f, facts) in self.facts.iter().enumerate() {
            for r in facts.references.iter().filter(|r| !r.test) {
                let Some(to) = self.resolve(&r.module, &r.path, 0).filter(|&to| to != f) else {
                    continue;
                };
                let target = module_of(self.files[to].trim_start_matches("src/"));
                if r.reexport && target.starts_with(&r.module) {
                    continue;
                }
                edges.entry((f, to)).or_insert(r.line);
            }
        }
        edges
    }

    /// The import cycles: each strongly connected set of files (more than one), with the
    /// dependencies inside it.
    fn cycles(&self) -> Vec<String> {
        let edges = self.edges();
        let n = self.files.len();
        let mut next = vec![Vec::new(); n];
        for &(a, b) in edges.keys() {
            next[a].push(b);
        }
        strongly_connected(&next)
            .into_iter()
            .filter(|set| set.len() > 1)
            .map(|set| {
                let inside: BTreeSet<usize> = set.iter().copied().collect();
                let mut text = String::new();
                for (&(a, b), line) in &edges {
                    if inside.contains(&a) && inside.contains(&b) {
                        text.push_str(&format!(
                            "\n    {}:{line} uses {}",
                            self.files[a], self.files[b]
                        ));
                    }
                }
                text
            })
            .collect()
    }
}

/// Tarjan's strongly connected components of the graph with successor lists `next`.
fn strongly_connected(next: &[Vec<usize>]) -> Vec<Vec<usize>> {
    struct State<'a> {
        next: &'a [Vec<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        stack: Vec<usize>,
        on_stack: Vec<bool>,
        counter: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(s: &mut State, v: usize) {
        s.index[v] = Some(s.counter);
        s.low[v] = s.counter;
        s.counter += 1;
        s.stack.push(v);
        s.on_stack[v] = true;
        for k in 0..s.next[v].len() {
            let w = s.next[v][k];
            match s.index[w] {
                None => {
                    visit(s, w);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(iw) if s.on_stack[w] => s.low[v] = s.low[v].min(iw),
                Some(_) => {}
            }
        }
        if Some(s.low[v]) == s.index[v] {
            let mut set = Vec::new();
            loop {
                let w = s.stack.pop().unwrap();
                s.on_stack[w] = false;
                set.push(w);
                if w == v {
                    break;
                }
            }
            s.out.push(set);
        }
    }
    let n = next.len();
    let mut s = State {
        next,
        index: vec![None; n],
        low: vec![0; n],
        stack: Vec::new(),
        on_stack: vec![false; n],
        counter: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if s.index[v].is_none() {
            visit(&mut s, v);
        }
    }
    s.out
}

/// Every `.rs` file under `src/`: (path relative to `src/`, text), sorted by path.
fn sources() -> Vec<(String, String)> {
    fn walk(dir: &Path, root: &Path, out: &mut Vec<(String, String)>) {
        for entry in std::fs::read_dir(dir).expect("src/ is readable") {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, root, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let relative = path.strip_prefix(root).unwrap().to_string_lossy();
                let text = std::fs::read_to_string(&path).unwrap();
                out.push((relative.replace('\\', "/"), text));
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = Vec::new();
    walk(&root, &root, &mut out);
    out.sort();
    out
}

#[test]
fn no_import_cycle_between_the_files_of_src() {
    let krate = Crate::read(&sources());
    // The reader must see the crate's real dependencies, or an empty graph would pass.
    let edges = krate.edges();
    assert!(
        edges.len() > krate.files.len(),
        "only {} dependencies between {} files: the reader misses them",
        edges.len(),
        krate.files.len()
    );
    let cycles = krate.cycles();
    assert!(
        cycles.is_empty(),
        "{} import cycle(s) between the files of src/ (move the shared item to the file that \
         owns it):{}",
        cycles.len(),
        cycles.join("\n  --")
    );
}

#[test]
fn no_file_of_src_is_long() {
    let krate = Crate::read(&sources());
    let long: Vec<String> = (0..krate.files.len())
        .filter(|&f| krate.facts[f].lines > MAX_FILE_LINES)
        .map(|f| format!("{} ({} lines)", krate.files[f], krate.facts[f].lines))
        .collect();
    assert!(
        long.is_empty(),
        "files over {MAX_FILE_LINES} lines: {}",
        long.join(", ")
    );
}

#[test]
fn no_function_of_src_is_long() {
    let krate = Crate::read(&sources());
    let mut long = Vec::new();
    let mut allowed_seen = HashSet::new();
    for (f, facts) in krate.facts.iter().enumerate() {
        for (name, first, last) in &facts.functions {
            let lines = last - first + 1;
            if lines <= MAX_FN_LINES {
                continue;
            }
            let file = krate.files[f].as_str();
            let allowed = LONG_FUNCTIONS
                .iter()
                .position(|&(lf, ln, _)| lf == file && ln == name);
            match allowed {
                Some(k) => {
                    allowed_seen.insert(k);
                }
                None => long.push(format!("{file}:{first} {name} ({lines} lines)")),
            }
        }
    }
    assert!(
        long.is_empty(),
        "functions over {MAX_FN_LINES} lines (split them into their stages, or name one in \
         LONG_FUNCTIONS with the reason it stays whole):\n  {}",
        long.join("\n  ")
    );
    let stale: Vec<String> = (0..LONG_FUNCTIONS.len())
        .filter(|k| !allowed_seen.contains(k))
        .map(|k| format!("{} {}", LONG_FUNCTIONS[k].0, LONG_FUNCTIONS[k].1))
        .collect();
    assert!(
        stale.is_empty(),
        "LONG_FUNCTIONS names functions that are no longer long (or no longer exist): {}",
        stale.join(", ")
    );
}

/// The reader on a small crate written here: a cycle through a re-export and a use tree, and
/// the traps around it (paths in comments and strings, a façade `mod.rs`, a test module, a
/// long function whose braces hide in literals).
fn planted() -> Vec<(String, String)> {
    let files = [
        ("lib.rs", "pub mod a;\npub mod b;\npub mod c;\n"),
        (
            "a/mod.rs",
            "mod inner;\npub use inner::Inner;\n// use crate::c::C;\nconst S: &str = \"crate::c::C\";\n",
        ),
        (
            "a/inner.rs",
            "use crate::b::{x::{self, X as Y}};\npub struct Inner;\n\
             #[cfg(test)]\nmod tests {\n    use crate::c::C;\n}\n",
        ),
        ("b/mod.rs", "pub mod x;\n"),
        ("b/x.rs", "pub struct X;\nfn f() { let _ = super::super::a::Inner; }\n"),
        ("c.rs", "use super::a::Inner;\npub struct C;\n"),
    ];
    files
        .iter()
        .map(|(p, t)| (p.to_string(), t.to_string()))
        .collect()
}

#[test]
fn the_reader_finds_a_planted_cycle_and_only_it() {
    let krate = Crate::read(&planted());
    let cycles = krate.cycles();
    assert_eq!(cycles.len(), 1, "{cycles:?}");
    assert!(
        cycles[0].contains("src/a/inner.rs:1 uses src/b/x.rs")
            && cycles[0].contains("src/b/x.rs:2 uses src/a/inner.rs"),
        "{}",
        cycles[0]
    );
    // c.rs uses a's item, but nothing in the crate uses c outside comments, strings and tests.
    let edges = krate.edges();
    let c = krate.files.iter().position(|f| f == "src/c.rs").unwrap();
    assert!(edges.keys().all(|&(_, to)| to != c), "{edges:?}");
}

#[test]
fn the_reader_measures_functions_past_braces_in_literals() {
    let source = "fn long() {\n    let s = \"}\";\n    let c = '}';\n    // }\n    /* } */\n    \
                  let r = r#\"}\"#;\n}\nfn short() -> [u8; 2] { [0; 2] }\ntrait T { fn f(&self); }\n";
    let facts = read_file(source, &Vec::new(), &|_, _| false);
    assert_eq!(
        facts.functions,
        vec![("long".to_string(), 1, 7), ("short".to_string(), 8, 8)]
    );
}

#[test]
fn the_reader_counts_a_reexport_that_its_file_uses() {
    let files = [
        ("lib.rs", "mod f;\n"),
        (
            "f/mod.rs",
            "mod a;\nmod b;\npub use a::A;\npub use b::B;\npub struct Front;\n\
             fn make(a: A) -> A { a }\n",
        ),
        ("f/a.rs", "use super::Front;\npub struct A;\n"),
        ("f/b.rs", "use super::Front;\npub struct B;\n"),
    ];
    let sources: Vec<(String, String)> = files
        .iter()
        .map(|(p, t)| (p.to_string(), t.to_string()))
        .collect();
    let cycles = Crate::read(&sources).cycles();
    assert_eq!(cycles.len(), 1, "{cycles:?}");
    assert!(
        cycles[0].contains("src/f/mod.rs:3 uses src/f/a.rs") && !cycles[0].contains("b.rs"),
        "{}",
        cycles[0]
    );
}
