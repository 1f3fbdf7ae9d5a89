# Answers a row must refuse in one line: a 100 000-character message, 2000 unknown keys, 300 levels of nesting.
STUDY = True
calls = [0]
def f(case):
    i = calls[0] % 3
    calls[0] += 1
    if i == 0:
        return {'status': 'failed', 'message': 'x' * 100000}
    if i == 1:
        return {'status': 'ok', 'pi1': 1.0, **{('k%d' % j): j for j in range(2000)}}
    return {'status': 'ok', 'pi1': 1.0, 'extra': eval('[' * 300 + ']' * 300)}
