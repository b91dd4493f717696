"""What a script reads and sets, without running it: `validate` finds the keys a tree's
scripts read that nothing sets (hrc_drake.known_values)."""

from hrc_drake.bt.script import Token, tokenize


def assigned_keys(code: str) -> list[str]:
    """The blackboard keys a script sets, without running it: each `key := value` or
    `key = value` whose value does not read the key itself (`n := n + 1` and `n += 1` need
    `n` set before)."""
    assigned = []
    for statement in _statements(tokenize(code)):
        names = [t.text for t in statement if t.kind == "name"]
        if len(statement) > 1 and statement[1].text in (":=", "=") and names[0] not in names[1:]:
            assigned.append(names[0])
    return assigned


def read_keys(code: str) -> list[str]:
    """The names a script reads (blackboard keys or enum names), without running it: every
    name but those it only assigns (`:=`, `=`); `+=` and the like read theirs too."""
    tokens = tokenize(code)
    return [
        token.text
        for token, following in zip(tokens, tokens[1:], strict=False)
        if token.kind == "name"
        and token.text not in ("true", "false")
        and following.text not in (":=", "=")
    ]


def _statements(tokens: list[Token]) -> list[list[Token]]:
    """The tokens of each `;`-separated statement."""
    statements = [[]]
    for token in tokens:
        if token.text == ";":
            statements.append([])
        elif token.kind != "end":
            statements[-1].append(token)
    return [s for s in statements if s]
