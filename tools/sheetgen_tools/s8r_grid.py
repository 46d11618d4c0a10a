"""The S8R elements of a structured shell grid, for the hand-written CalculiX
reference decks of the tests (a strip, a folded strip)."""


def s8r_elements(rows, cols, node):
    """The `*ELEMENT, TYPE=S8R, ELSET=EALL` block, as deck lines, over a grid of
    `rows` x `cols` nodes (both odd: corner and mid-side nodes alternate), where
    node(i, j) is the id of the node in row i, column j; elements numbered from 1
    in row-major order, corners first and then mid-sides as CalculiX wants."""
    lines = ["*ELEMENT, TYPE=S8R, ELSET=EALL"]
    e = 0
    for i in range(0, rows - 1, 2):
        for j in range(0, cols - 1, 2):
            e += 1
            q = [node(i, j), node(i + 2, j), node(i + 2, j + 2), node(i, j + 2),
                 node(i + 1, j), node(i + 2, j + 1), node(i + 1, j + 2), node(i, j + 1)]
            lines.append("%d, " % e + ", ".join(map(str, q)))
    return lines
