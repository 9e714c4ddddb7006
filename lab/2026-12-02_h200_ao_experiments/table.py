import json,glob,gzip,statistics,collections,sys
def load(f):  # plain or gzip (X.json.gz)
    raw=open(f,'rb').read()
    return json.loads(gzip.decompress(raw) if f.endswith('.gz') or raw[:2]==b'\x1f\x8b' else raw)
root=sys.argv[1]
res=collections.defaultdict(lambda: collections.defaultdict(list)); dig={}
for f in sorted(glob.glob(root+'/*.r*/manifest.json')+glob.glob(root+'/*.r*/manifest.json.gz')):
    v,r=f.split('/')[-2].rsplit('.',1)
    m=load(f)
    for c in m['configurations']:
        key=(v,c['id'].split('/')[1],c['api']); rr=c['renders'][0]
        if rr['error']: print(v,key,rr['error'][:200])
        for t in rr['timings']: res[key][t['pass']].append(t['median_ms'])
        dig[key]=' '.join(i['name']+'='+i['digest'][-6:] for i in rr['images'])
for key in sorted(res):
    d=res[key]
    print(' '.join(key).ljust(34), ' '.join(f"{p}={statistics.median(d[p]):.4f}" for p in d), ' sum=%.4f'%sum(statistics.median(d[p]) for p in d), dig[key])
