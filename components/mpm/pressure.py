"""Pressure boundary conditions on MPM particles (`<PhysicalBC><MPM><pressure>`): TODO."""


class PressureBCs:
    @classmethod
    def read(cls, root, mpm):
        pbc = root.child("PhysicalBC")
        if pbc is None:
            return None
        raise pbc.error("<PhysicalBC> is not supported yet")
