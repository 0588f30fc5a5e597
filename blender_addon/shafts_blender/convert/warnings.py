"""The list of approximations an export made.

Every feature that has no exact counterpart in the scene format is rendered
approximately and recorded here as one full sentence that names the Blender
object (or material) and says what is done instead. The list keeps the order
of first occurrence and drops repeats.
"""


class Warnings:
    def __init__(self):
        self.sentences = []
        self._seen = set()

    def add(self, sentence):
        if sentence not in self._seen:
            self._seen.add(sentence)
            self.sentences.append(sentence)

    def __iter__(self):
        return iter(self.sentences)

    def __len__(self):
        return len(self.sentences)
