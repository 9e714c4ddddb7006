"""Candidate metrics for subtle, systematic errors, on one channel (the
luminance of a colour image): the gate's own (mean abs, RMSE, max abs, share
over 0.01) and the candidates: shares over lower thresholds, the signed
mean, changes a 4-neighbour shares (coherent), 8 px tiles' signed mean and
median and the share of tiles biased one way, a 5x5 box-blurred difference,
and the error where the reference's blurred AO is under 0.9 (occluded).
"""
import math
def lum(w,h,c,px):
    if c==1: return px
    return [0.2126*px[i*c]+0.7152*px[i*c+1]+0.0722*px[i*c+2] for i in range(w*h)]

def metrics(w,h,a,b,ao_ref=None,tile=8):
    """a new, b ref, single channel lists."""
    n=w*h
    d=[a[i]-b[i] for i in range(n)]
    ad=[abs(x) for x in d]
    m={}
    m['mean_abs']=sum(ad)/n
    m['rmse']=math.sqrt(sum(x*x for x in d)/n)
    m['max_abs']=max(ad)
    m['over']=sum(1 for x in ad if x>0.01)/n
    for t in (0.002,0.003,0.005): m['over_%g'%t]=sum(1 for x in ad if x>t)/n
    m['bias']=abs(sum(d)/n)
    # isolated-pixel suppression: a pixel counts only if some 4-neighbour moved the same way by half as much
    cnt=0; s=0.0
    for y in range(h):
        for x in range(w):
            i=y*w+x; v=d[i]
            if abs(v)<=0.002: continue
            ok=False
            for dx,dy in ((1,0),(-1,0),(0,1),(0,-1)):
                X,Y=x+dx,y+dy
                if 0<=X<w and 0<=Y<h:
                    u=d[Y*w+X]
                    if u*v>0 and abs(u)>=0.5*abs(v) : ok=True;break
            if ok: cnt+=1; s+=abs(v)
    m['coherent_share']=cnt/n
    m['coherent_mean']=s/n
    # tiles: signed mean per tile
    tb=[]; 
    for ty in range(0,h,tile):
        for tx in range(0,w,tile):
            vals=[d[y*w+x] for y in range(ty,min(h,ty+tile)) for x in range(tx,min(w,tx+tile))]
            vs=sorted(vals); med=vs[len(vs)//2]
            tb.append((sum(vals)/len(vals),med))
    m['tile_mean_max']=max(abs(t[0]) for t in tb)
    m['tile_median_max']=max(abs(t[1]) for t in tb)
    for eps in (0.0005,0.001):
        pos=sum(1 for t in tb if t[0]>eps); neg=sum(1 for t in tb if t[0]<-eps)
        m['tiles_biased_%g'%eps]=max(pos,neg)/len(tb)
    # box-blurred difference 5x5
    r=2; best=0.0
    # integral image
    I=[[0.0]*(w+1) for _ in range(h+1)]
    for y in range(h):
        row=0.0
        for x in range(w):
            row+=d[y*w+x]; I[y+1][x+1]=I[y][x+1]+row
    for y in range(h):
        y0=max(0,y-r); y1=min(h,y+r+1)
        for x in range(w):
            x0=max(0,x-r); x1=min(w,x+r+1)
            v=(I[y1][x1]-I[y0][x1]-I[y1][x0]+I[y0][x0])/((y1-y0)*(x1-x0))
            if abs(v)>best: best=abs(v)
    m['blur5_max']=best
    if ao_ref is not None:
        occ=[i for i in range(n) if ao_ref[i]<0.9]
        if occ:
            m['occl_mean_abs']=sum(ad[i] for i in occ)/len(occ)
            m['occl_bias']=abs(sum(d[i] for i in occ)/len(occ))
        else:
            m['occl_mean_abs']=0; m['occl_bias']=0
    return m
