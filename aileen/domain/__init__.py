"""The domain, declared once: the agent's senses (channels), the qualitative calculi its
perception computes, the relations the trainer can lay out and grade, and the primitive
actions of the body.

Everything else reads these declarations; nothing else lists channels, relations or actions.
The declarations describe the senses, the calculi and the body — never what a word means: the
agent learns meanings, and a `TrainerRelation`'s `accepts` (the teacher's ground truth) is
never visible to it. docs/architecture.md has the recipes "add a channel / a relation / an
action".
"""
