# issue 33 (6): a record name that is not UTF-8 (surrogate-escaped) must still give an answer or a ValueError
{'scene': 'pair', 'pulse': 'record', 'record': 'cases/records/real/\udcffAZF225.AT2', 'tp': 0.5, 'directivity': 'normal', 'pi2': 1, 'pi3': 0.5, 'eps': 0.5, 'pi5': 2, 'pi6': 1}
