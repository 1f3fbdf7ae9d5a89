# issue 33 (11): an int too large for a double
{'scene': 'wall', 'pulse': 'sine', 'directivity': 'normal', 'pi2': 10**400, 'pi3': 0.5, 'eps': 0.5}
