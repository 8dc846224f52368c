"""`<DataAnalysis>` modules of MPM decks: TODO."""


class ParticleExtract:
    def __init__(self, root, mpm):
        self.active = False
        da = root.child("DataAnalysis")
        if da is not None:
            da.mark_used()
