#!/usr/bin/env python3
"""Structural limits of one source folder (the implicit module's, by default).

Checks, and prints every violation with file:line:
  - no include cycle among the folder's headers (a header's includes of the folder, followed
    through headers; a .cpp may include its own header and any other),
  - no file over --max-file-lines lines,
  - no function definition over --max-function-lines lines, from its signature's first line
    to its closing brace. Functions are found by brace matching: a block whose opening text
    ends with a parameter list (and is not if/for/while/switch/catch, a lambda's body inside
    another function counting as part of that function) and which sits directly in a
    namespace, class or struct, or at file scope.
Exits 1 when anything is over, 0 otherwise.
"""
import argparse
import os
import re
import sys

CONTROL = re.compile(r'\b(if|for|while|switch|catch|do|else)\s*(\(|$)')
SCOPE = re.compile(r'\b(namespace|class|struct|union|enum)\b')


def strip_code(text):
    """The text with comments and string/char literals blanked, line breaks kept."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            i = n if j < 0 else j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append('\n' * text.count('\n', i, j))
            i = j
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == '\\' else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return ''.join(out)


def long_functions(path, limit):
    code = strip_code(open(path, encoding='utf-8').read())
    # Preprocessor lines carry no braces that matter here.
    code = '\n'.join('' if l.lstrip().startswith('#') else l for l in code.split('\n'))
    stack = []  # entries: (kind, start line)
    head_start, head = None, ''
    line = 1
    found = []
    for c in code:
        if c == '\n':
            line += 1
            head += ' '
            continue
        if c == '{':
            text = head.strip()
            in_function = any(kind == 'function' for kind, _ in stack)
            if in_function:
                kind = 'block'
            elif SCOPE.search(text) and not text.endswith(')') and '(' not in text.split('{')[-1]:
                kind = 'scope'
            elif re.search(r'\)\s*(const|override|final|noexcept|->[^{]*|:[^{]*)*\s*$', text) \
                    and not CONTROL.search(text):
                kind = 'function'
            else:
                kind = 'block'
            stack.append((kind, head_start if head_start is not None else line))
            head_start, head = None, ''
        elif c == '}':
            if stack:
                kind, start = stack.pop()
                if kind == 'function' and line - start + 1 > limit:
                    found.append((start, line - start + 1))
            head_start, head = None, ''
        elif c == ';':
            head_start, head = None, ''
        else:
            if head_start is None and not c.isspace():
                head_start = line
            head += c
    return found


def header_includes(folder, prefix):
    graph = {}
    for name in os.listdir(folder):
        if not name.endswith('.h'):
            continue
        text = open(os.path.join(folder, name), encoding='utf-8').read()
        graph[name] = [m for m in re.findall(r'#include "' + re.escape(prefix) + r'([^"/]+\.h)"', text)]
    return graph


def include_cycles(graph):
    cycles, state = [], {}

    def visit(node, path):
        state[node] = 'open'
        for nxt in graph.get(node, []):
            if state.get(nxt) == 'open':
                cycles.append(path[path.index(nxt):] + [nxt] if nxt in path else [node, nxt])
            elif nxt not in state:
                visit(nxt, path + [nxt])
        state[node] = 'done'

    for node in sorted(graph):
        if node not in state:
            visit(node, [node])
    return cycles


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('folder')
    parser.add_argument('--include-prefix', default='libobj/implicit/',
                        help='how the folder\'s own headers are included')
    parser.add_argument('--max-file-lines', type=int, default=600)
    parser.add_argument('--max-function-lines', type=int, default=80)
    args = parser.parse_args()
    problems = []
    for name in sorted(os.listdir(args.folder)):
        if not name.endswith(('.h', '.cpp')):
            continue
        path = os.path.join(args.folder, name)
        count = open(path, encoding='utf-8').read().count('\n')
        if count > args.max_file_lines:
            problems.append(f'{path}:1: {count} lines (limit {args.max_file_lines})')
        for start, length in long_functions(path, args.max_function_lines):
            problems.append(f'{path}:{start}: function of {length} lines '
                            f'(limit {args.max_function_lines})')
    for cycle in include_cycles(header_includes(args.folder, args.include_prefix)):
        problems.append(f'{args.folder}: include cycle ' + ' -> '.join(cycle))
    for p in problems:
        print(p)
    print(f'{len(problems)} structural problem(s)')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
