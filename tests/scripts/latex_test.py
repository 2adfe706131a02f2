#!/usr/bin/python3
"""The LaTeX tables (studies/table.cpp): tables generated now (a study file whose labels hold
LaTeX's special characters) and committed ones (every reports/*.tex), checked as text and
compiled.

    latex_test.py text    NSBENCH_STUDY SOURCE_DIR   structure of every table, always
    latex_test.py compile NSBENCH_STUDY SOURCE_DIR   all tables in one minimal document (the
                                                     preamble their '% needs' comments name),
                                                     through pdflatex or lualatex

The text check: environments opened and closed in order, braces balanced, every row with as
many cells as the column specification (\\multicolumn{n} counting n), '$' paired in each cell,
no unescaped '#', '%', '_' or '^' outside math; in a siunitx S column every cell a number that
fits the column's table-format, or braced text (headers, n/a), never bare text; siunitx named
in '% needs' when a table uses it. Both modes first show that their check fails on broken
copies of a generated table. compile exits 77 (CTest: skipped) when neither engine is on PATH
(Debian texlive-latex-base, texlive-latex-recommended and texlive-science hold the packages)."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

# Committed tables: every one in reports/.
COMMITTED = "reports"
# Labels with every character LaTeX treats specially: the writer must escape them.
HOSTILE_LABEL = r'CD-Lagrange #1 & 50% {x_1^2} ~ \\ $a$ <b> |c|'
STUDY_FILE = """[study]
title = "Specials: # & % _ ^ ~ $ {{ }} \\\\ < > |"
t_end = 0.5
targets = [1e-2]

[[problem]]
name = "bouncing-mass"
label = "mass_1, e = 90%"
parameters = {{ e = 0.9, h0 = 1.0 }}

[[integrator]]
name = "cd-lagrange"
label = '{label}'
steps = [1e-2, 1e-3]

[[integrator]]
name = "moreau-jean"
label = "Moreau-Jean, theta = 1/2"
parameters = {{ theta = 0.5 }}
steps = [1e-2, 1e-3]

[reference]
solution = "exact"

[[measure]]
kind = "error"
observable = "u"
norm = "max"
"""
TABLE_ENVIRONMENTS = ("longtable", "tabular")
# Row-level commands that carry no cells.
RULES = re.compile(r"\\(toprule|midrule|bottomrule|endfirsthead|endhead|endfoot|endlastfoot|hline)\b")
# A number as siunitx reads it in an S column, and a table-format (the same shape: the digits
# counted, a '-' reserving room for a sign).
NUMBER = re.compile(r"(-?)(\d+)(?:\.(\d+))?(?:e(-?)(\d+))?")


def uncommented(text):
    """The text without comments: from an unescaped % to the end of its line."""
    return "\n".join(re.sub(r"(?<!\\)%.*", "", line) for line in text.splitlines())


def group(text, start):
    """(content, end) of the brace group opening at text[start] == '{'."""
    depth = 0
    for i in range(start, len(text)):
        if text[i] == "\\":
            continue
        if text[i] == "{" and text[i - 1] != "\\":
            depth += 1
        elif text[i] == "}" and text[i - 1] != "\\":
            depth -= 1
            if depth == 0:
                return text[start + 1:i], i + 1
    raise ValueError("unclosed brace group")


def spec_columns(spec):
    """Columns of a tabular specification, each (type, table-format or None): l, c, r,
    p{width} and siunitx's S[options]; @{...} adds none."""
    columns, i = [], 0
    while i < len(spec):
        if spec[i] in "@p" and spec[i + 1:i + 2] == "{":
            if spec[i] == "p":
                columns.append(("p", None))
            _, i = group(spec, i + 1)
            continue
        if spec[i] == "S":
            i += 1
            options = ""
            if spec[i:i + 1] == "[":
                end = spec.index("]", i)
                options, i = spec[i + 1:end], end + 1
            m = re.search(r"table-format\s*=\s*([^,]*)", options)
            columns.append(("S", m.group(1).strip() if m else None))
            continue
        if spec[i] in "lcr":
            columns.append((spec[i], None))
        i += 1
    return columns


def fits(number, table_format):
    """Whether a number (NUMBER's match) has room in a table-format: sign, digits, exponent."""
    f = NUMBER.fullmatch(table_format)
    if f is None:
        return False
    sign, integer, decimals, exp_sign, exponent = number.groups()
    room = [int(g) if g else 0 for g in (f.group(2), f.group(3), f.group(5))]
    return ((not sign or f.group(1)) and len(integer) <= room[0] and len(decimals or "") <= room[1]
            and (exponent is None or (f.group(5) and (not exp_sign or f.group(4)) and len(exponent) <= room[2])))


def s_cell(cell, table_format):
    """A problem of a cell in an S column (None: a number that fits, braced text or empty)."""
    cell = cell.strip()
    try:
        if not cell or (cell[0] == "{" and group(cell, 0)[1] == len(cell)):
            return None
    except ValueError:
        return f"a brace left open in '{cell}'"
    number = NUMBER.fullmatch(cell)
    if number is None:
        return f"bare text '{cell}' in an S column (siunitx would parse it as a number; brace it)"
    if table_format is not None and not fits(number, table_format):
        return f"'{cell}' does not fit its S column's table-format={table_format}"
    return None


def split_top(text, sep):
    """text split at unescaped sep outside brace groups."""
    parts, depth, cur, i = [], 0, "", 0
    while i < len(text):
        c = text[i]
        if c == "\\" and i + 1 < len(text):
            if depth == 0 and text.startswith(sep, i) and sep == "\\\\":
                parts.append(cur)
                cur, i = "", i + 2
                continue
            cur += text[i:i + 2]
            i += 2
            continue
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
        if depth == 0 and sep == c:
            parts.append(cur)
            cur = ""
        else:
            cur += c
        i += 1
    parts.append(cur)
    return parts


def outside_math(cell):
    """The cell's text outside $...$ (unescaped dollars) and outside labels (\\label, \\ref)."""
    cell = re.sub(r"\\(label|ref)\{[^}]*\}", "", cell)
    return "".join(re.split(r"(?<!\\)\$", cell)[0::2])


def unescaped(text, specials):
    """The characters of specials found unescaped in text outside math."""
    text = outside_math(text)
    return [c for c in specials if re.search(r"(?<!\\)" + re.escape(c), text)]


def check_text(name, text):
    """Problems found in one table's text (empty: none)."""
    problems = []
    body = uncommented(text)
    depth = 0
    for i, c in enumerate(body):
        if c in "{}" and (i == 0 or body[i - 1] != "\\" or body[i - 2:i] == "\\\\"):
            depth += 1 if c == "{" else -1
            if depth < 0:
                problems.append(f"{name}: '}}' closes nothing at offset {i}")
                depth = 0
    if depth:
        problems.append(f"{name}: {depth} brace(s) left open")
    stack = []
    for m in re.finditer(r"\\(begin|end)\{([^}]*)\}", body):
        if m.group(1) == "begin":
            stack.append(m.group(2))
        elif not stack or stack.pop() != m.group(2):
            problems.append(f"{name}: \\end{{{m.group(2)}}} does not close the innermost environment")
    if stack:
        problems.append(f"{name}: environments left open: {', '.join(stack)}")
    tables = [m for m in re.finditer(r"\\begin\{(longtable|tabular)\}", body)]
    if len(tables) != 1:
        problems.append(f"{name}: {len(tables)} tables (expected one longtable or tabular)")
        return problems
    env = tables[0].group(1)
    spec, start = group(body, tables[0].end())
    end = body.find(f"\\end{{{env}}}", start)
    columns = spec_columns(spec)
    rows = 0
    uses_siunitx = "\\num{" in body or any(kind == "S" for kind, _ in columns)
    if uses_siunitx and "siunitx" not in (packages(text) or ""):
        problems.append(f"{name}: siunitx used but not named in '% needs'")
    for row in split_top(body[start:end], "\\\\"):
        row = RULES.sub("", row).strip()
        if not row:
            continue
        if row.startswith("\\caption"):
            # The title: one cell spanning the table, '&' included.
            problems += [f"{name}: unescaped '{c}' in the caption '{row[:60]}'" for c in unescaped(row, "#_^%&")]
            continue
        rows += 1
        cells = split_top(row, "&")
        width = 0
        if len(cells) == len(columns):
            for cell, (kind, table_format) in zip(cells, columns):
                problem = s_cell(cell, table_format) if kind == "S" else None
                if problem:
                    problems.append(f"{name}: {problem}")
        for cell in cells:
            m = re.match(r"\s*\\multicolumn\{(\d+)\}", cell)
            width += int(m.group(1)) if m else 1
            if len(re.findall(r"(?<!\\)\$", cell)) % 2:
                problems.append(f"{name}: unpaired '$' in cell '{cell.strip()}'")
            problems += [f"{name}: unescaped '{c}' in cell '{cell.strip()}'" for c in unescaped(cell, "#_^%")]
        if width != len(columns):
            problems.append(f"{name}: a row of {width} cells in a table of {len(columns)} columns: '{row[:80]}'")
    if rows < 2:
        problems.append(f"{name}: {rows} row(s): expected a header and at least one row")
    outside = body[:tables[0].start()] + body[end:]
    for special in "#_^&":
        for m in re.finditer(r"(?<!\\)" + re.escape(special), outside_math(outside)):
            problems.append(f"{name}: unescaped '{special}' outside the table: '{outside[max(0, m.start() - 30):m.start() + 10]}'")
    return problems


def packages(text):
    """The \\usepackage line the table's '% needs' comment names."""
    m = re.search(r"^% needs (\\usepackage\{[^}]*\})", text, re.M)
    return m.group(1) if m else None


def generated_tables(study, work):
    """The .tex tables of a study run from STUDY_FILE (hostile labels) into work/gen."""
    path = os.path.join(work, "specials.toml")
    with open(path, "w") as f:
        f.write(STUDY_FILE.format(label=HOSTILE_LABEL))
    out = os.path.join(work, "gen")
    subprocess.run([study, "run", path, "--out", out], check=True, capture_output=True, text=True)
    return sorted(os.path.join(out, f) for f in os.listdir(out) if f.endswith(".tex"))


def shape(cell):
    """What TeX and siunitx see of a cell, digits and words aside: 5.22e-2 as 0.0e-0,
    cd-lagrange as a-a; commands (\\_, $\\theta$, \\textbar{}) and braces kept."""
    return re.sub(r"(?<![\\A-Za-z])[A-Za-z]+", "a", re.sub(r"\d+", "0", cell))


def sampled(text):
    """The table with only the body rows (one a line, after \\endlastfoot) that bring a cell of
    a shape not seen in its column before: every kind of cell of every column still goes
    through TeX, in a fraction of the time (siunitx takes about 2 ms a number; the committed
    tables hold some 30000). (table, rows kept, rows)."""
    if "\\endlastfoot" not in text:
        return text, None, None
    start = text.index("\n", text.index("\\endlastfoot")) + 1
    end = text.index("\\end{longtable}", start)
    rows, seen, kept = text[start:end].splitlines(keepends=True), set(), []
    for row in rows:
        cells = {(i, shape(c)) for i, c in enumerate(row.split(" & "))}
        if not cells <= seen:
            seen |= cells
            kept.append(row)
    return text[:start] + "".join(kept) + text[end:], len(kept), len(rows)


def compile_tables(engine, texts, work):
    """None if the tables (name -> text) compile in one minimal document loading every package
    their '% needs' comments name, else the end of the log."""
    names = sorted({n.strip() for t in texts.values() for n in packages(t)[len("\\usepackage{"):-1].split(",")})
    body = []
    for i, (name, text) in enumerate(texts.items()):
        path = os.path.join(work, f"table{i}.tex")
        with open(path, "w") as f:
            f.write(text)
        body.append(f"% {name}\n\\input{{{path}}}\n")
    with open(os.path.join(work, "doc.tex"), "w") as f:
        f.write(f"\\documentclass{{article}}\n\\usepackage{{{','.join(names)}}}\n\\begin{{document}}\n"
                f"{''.join(body)}\\end{{document}}\n")
    r = subprocess.run([engine, "-interaction=nonstopmode", "-halt-on-error", "doc.tex"], cwd=work,
                       capture_output=True, text=True)
    return None if r.returncode == 0 else r.stdout[-1500:]


def check_compile(engine, texts, work):
    """Problems of the tables compiled together; when that fails, each alone names the culprits."""
    log = compile_tables(engine, texts, work)
    if log is None:
        return []
    alone = [f"{name}: {engine} failed:\n{l}" for name, text in texts.items()
             if (l := compile_tables(engine, {name: text}, work)) is not None]
    return alone or [f"the tables together: {engine} failed:\n{log}"]


def first_data_row(text, edit):
    """text with its first body row (the line after \\endlastfoot) replaced by edit(row)."""
    start = text.index("\n", text.index("\\endlastfoot")) + 1
    end = text.index("\n", start)
    return text[:start] + edit(text[start:end]) + text[end:]


# Broken copies of a generated table (the work-precision one: S columns, n/a, the hostile
# label): the check must flag each. (what is broken, edit, also fails to compile)
BROKEN = [
    ("bare text in an S column", lambda t: t.replace("& {n/a} &", "& n/a &", 1), False),
    ("a header unbraced in an S column", lambda t: re.sub(r" & \{([^{}$\\]*)\}", r" & \1", t, count=1), True),
    ("a cell dropped", lambda t: first_data_row(t, lambda r: r.rsplit(" & ", 1)[0] + " \\\\"), False),
    ("a number wider than its table-format",
     lambda t: re.sub(r"table-format=(-?\d+)\.(\d+)", lambda m: f"table-format={m[1]}.{int(m[2]) - 1}", t, count=1),
     False),
    ("siunitx not named in '% needs'", lambda t: t.replace("longtable,siunitx}", "longtable}"), True),
    ("an unescaped '#'", lambda t: t.replace("\\#", "#", 1), True),
    ("a brace left open", lambda t: t.replace("\\end{longtable}\n}", "\\end{longtable}\n", 1), False),
]


def check_catches(mode, engine, sample_path, work):
    """Failures of the check to flag the broken copies of the sample table."""
    with open(sample_path) as f:
        sample = f.read()
    failures = []
    for what, edit, breaks_compile in BROKEN:
        broken = edit(sample)
        if broken == sample:
            failures.append(f"{what}: the edit does not apply to {sample_path}")
        elif mode == "text" and not check_text(what, broken):
            failures.append(f"the text check passes a table with {what}")
        elif mode == "compile" and breaks_compile and compile_tables(engine, {what: broken}, work) is None:
            failures.append(f"{engine} compiles a table with {what}")
    return failures


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in ("text", "compile"):
        print(__doc__)
        return 2
    mode, study, source = sys.argv[1:]
    engine = next((e for e in ("pdflatex", "lualatex") if shutil.which(e)), None)
    if mode == "compile" and engine is None:
        print("SKIPPED: no pdflatex or lualatex on PATH (Debian texlive-latex-base, texlive-latex-recommended, "
              "texlive-science)")
        return 77
    failures, note = [], ""
    with tempfile.TemporaryDirectory() as work:
        generated = generated_tables(study, work)
        committed_dir = os.path.join(source, COMMITTED)
        committed = sorted(os.path.join(committed_dir, f) for f in os.listdir(committed_dir) if f.endswith(".tex"))
        if len(generated) < 3 or not committed:
            failures.append(f"{len(generated)} generated tables (expected 3), {len(committed)} committed")
        sample = next((p for p in generated if p.endswith("_work_precision.tex")), None)
        if sample is None:
            failures.append("the study file wrote no work-precision table")
        else:
            failures += check_catches(mode, engine, sample, work)
        texts = {}
        for path in generated + committed:
            with open(path) as f:
                texts[path] = f.read()
            if packages(texts[path]) is None:
                failures.append(f"{path}: no '% needs \\usepackage{{...}}' comment")
                del texts[path]
        if mode == "text":
            for path, text in texts.items():
                failures += check_text(path, text)
            # The hostile label reached a table, escaped (the check above would flag it raw), and
            # the numbers went to S columns.
            gen = "".join(texts.get(p, "") for p in generated)
            if "CD-Lagrange \\#1 \\& 50\\%" not in gen:
                failures.append("the hostile label is not in the generated tables, escaped")
            if "S[table-format=" not in gen:
                failures.append("the generated tables have no siunitx S column")
        else:
            # Committed tables are large: each compiled with a sample of its rows (its every
            # cell checked as text by the text mode).
            counts = [0, 0]
            for path in committed:
                if path in texts:
                    texts[path], kept, rows = sampled(texts[path])
                    counts = [counts[0] + (kept or 0), counts[1] + (rows or 0)]
            note = f" (committed: {counts[0]} of their {counts[1]} rows, one of each shape of cell)"
            failures += check_compile(engine, texts, work)
    for f in failures:
        print("FAIL:", f)
    print(f"{len(generated) + len(committed)} tables ({len(generated)} generated, {len(committed)} committed), "
          f"{mode}{note}: {'ok' if not failures else f'{len(failures)} failure(s)'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
