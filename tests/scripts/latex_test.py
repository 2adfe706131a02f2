#!/usr/bin/python3
"""The LaTeX tables (studies/table.cpp): tables generated now (a study file whose labels hold
LaTeX's special characters) and committed ones (reports/*.tex), checked as text and compiled.

    latex_test.py text    NSBENCH_STUDY SOURCE_DIR   structure of every table, always
    latex_test.py compile NSBENCH_STUDY SOURCE_DIR   each table in a minimal document (the
                                                     preamble its '% needs' comment names),
                                                     through pdflatex or lualatex

The text check: environments opened and closed in order, braces balanced, every row with as
many cells as the column specification (\\multicolumn{n} counting n), '$' paired in each cell,
no unescaped '#', '%', '_' or '^' outside math. compile exits 77 (CTest: skipped) when
neither engine is on PATH (Debian texlive-latex-extra has both packages the tables need)."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

# Committed tables: one longtable of the current writer, one tabular of the earlier one.
COMMITTED = ["reports/bouncing_mass.tex", "reports/claims.tex"]
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
    """Columns of a tabular specification: l, c, r and p{width}; @{...} adds none."""
    count, i = 0, 0
    while i < len(spec):
        if spec[i] in "@p" and spec[i + 1:i + 2] == "{":
            count += spec[i] == "p"
            _, i = group(spec, i + 1)
            continue
        count += spec[i] in "lcr"
        i += 1
    return count


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
    for row in split_top(body[start:end], "\\\\"):
        row = RULES.sub("", row).strip()
        if not row or row.startswith("\\caption"):
            continue
        rows += 1
        cells = split_top(row, "&")
        width = 0
        for cell in cells:
            m = re.match(r"\s*\\multicolumn\{(\d+)\}", cell)
            width += int(m.group(1)) if m else 1
            if len(re.findall(r"(?<!\\)\$", cell)) % 2:
                problems.append(f"{name}: unpaired '$' in cell '{cell.strip()}'")
            text_part = outside_math(cell)
            for special in "#_^%":
                if re.search(r"(?<!\\)" + re.escape(special), text_part):
                    problems.append(f"{name}: unescaped '{special}' in cell '{cell.strip()}'")
        if width != columns:
            problems.append(f"{name}: a row of {width} cells in a table of {columns} columns: '{row[:80]}'")
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


def compile_table(engine, tex_path, text, work):
    """None if the table compiles in a minimal document, else the end of the log."""
    doc = os.path.join(work, "doc.tex")
    with open(doc, "w") as f:
        f.write(f"\\documentclass{{article}}\n{packages(text)}\n\\begin{{document}}\n\\input{{{tex_path}}}\n\\end{{document}}\n")
    r = subprocess.run([engine, "-interaction=nonstopmode", "-halt-on-error", "doc.tex"], cwd=work,
                       capture_output=True, text=True)
    return None if r.returncode == 0 else r.stdout[-1500:]


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in ("text", "compile"):
        print(__doc__)
        return 2
    mode, study, source = sys.argv[1:]
    engine = next((e for e in ("pdflatex", "lualatex") if shutil.which(e)), None)
    if mode == "compile" and engine is None:
        print("SKIPPED: no pdflatex or lualatex on PATH (Debian texlive-latex-extra)")
        return 77
    failures = []
    with tempfile.TemporaryDirectory() as work:
        files = generated_tables(study, work) + [os.path.join(source, f) for f in COMMITTED]
        if len(files) < 3:
            failures.append(f"the study file produced {len(files) - len(COMMITTED)} tables")
        for path in files:
            with open(path) as f:
                text = f.read()
            if packages(text) is None:
                failures.append(f"{path}: no '% needs \\usepackage{{...}}' comment")
                continue
            if mode == "text":
                failures += check_text(path, text)
            else:
                log = compile_table(engine, path, text, work)
                if log is not None:
                    failures.append(f"{path}: {engine} failed:\n{log}")
        if mode == "text":
            # The hostile label reached a table, escaped (the check above would flag it raw).
            gen = "".join(open(p).read() for p in files[:-len(COMMITTED)])
            if "CD-Lagrange \\#1 \\& 50\\%" not in gen:
                failures.append("the hostile label is not in the generated tables, escaped")
    for f in failures:
        print("FAIL:", f)
    print(f"{len(files)} tables, {mode}: {'ok' if not failures else f'{len(failures)} failure(s)'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
