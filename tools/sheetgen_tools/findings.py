"""What a check found: the numbers it measured and what failed, one line each.
The checks of verify.py write into one Findings per output folder."""
import dataclasses


@dataclasses.dataclass
class Findings:
    lines: list = dataclasses.field(default_factory=list)     # "<load>: <what was measured>"
    failures: list = dataclasses.field(default_factory=list)  # "<load>: <what failed>"

    def note(self, line):
        self.lines.append(line)

    def fail(self, line):
        self.failures.append(line)

    def failed_loads(self):
        """The loads with at least one failure (the text before the first colon)."""
        return {f.split(":")[0] for f in self.failures}
